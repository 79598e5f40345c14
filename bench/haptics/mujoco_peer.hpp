#pragma once
// The peer the haptics benchmarks compare against: MuJoCo stepping a model given as MJCF text,
// with a force on a body (xfrc_applied) and how deep its bodies sink into what they rest on.
#ifdef WYSIWYF_HAVE_MUJOCO
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <string>

#include "scene/body.hpp"

namespace wysiwyf::haptics {

class MujocoScene {
 public:
  explicit MujocoScene(const std::string& xml) {
    vfs_ = std::make_unique<mjVFS>();  // large: not on the stack
    mj_defaultVFS(vfs_.get());
    mj_makeEmptyFileVFS(vfs_.get(), "scene.xml", static_cast<int>(xml.size()));
    std::memcpy(vfs_->filedata[vfs_->nfile - 1], xml.data(), xml.size());
    char error[1000] = "";
    m_ = mj_loadXML("scene.xml", vfs_.get(), error, sizeof error);
    if (!m_) {
      error_ = error;
      return;
    }
    d_ = mj_makeData(m_);
    for (int i = 0; i < 500; ++i) mj_step(m_, d_);  // settle
  }
  ~MujocoScene() {
    if (d_) mj_deleteData(d_);
    if (m_) mj_deleteModel(m_);
    if (vfs_) mj_deleteVFS(vfs_.get());
  }
  MujocoScene(const MujocoScene&) = delete;
  MujocoScene& operator=(const MujocoScene&) = delete;

  const std::string& error() const { return error_; }
  // A force on free body `body` (0: the first after the world), held until changed.
  void push(int body, const Vec3& f) {
    for (int k = 0; k < 3; ++k) d_->xfrc_applied[6 * (body + 1) + k] = f[k];
  }
  void step() { mj_step(m_, d_); }
  // Whether MuJoCo ran out of room for contacts or constraints (and dropped some).
  bool overflowed() const {
    return d_->warning[mjWARN_CONTACTFULL].number > 0 || d_->warning[mjWARN_CNSTRFULL].number > 0;
  }
  // How far below `rest_z` free body `body`'s centre is (its free joint's z).
  double sink(int body, double rest_z) const { return rest_z - d_->qpos[7 * body + 2]; }

 private:
  std::unique_ptr<mjVFS> vfs_;
  mjModel* m_ = nullptr;
  mjData* d_ = nullptr;
  std::string error_;
};

}  // namespace wysiwyf::haptics
#endif
