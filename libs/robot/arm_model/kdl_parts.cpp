// The KDL workspace: the chain built from the loaded joints and bodies, and the solvers and
// buffers the hot calls use, sized once.
#include "arm_model/kdl_parts.hpp"

#include "arm_model/arm_model.hpp"

namespace wysiwyf::robot {
namespace detail {
namespace {

KDL::Chain with_base_slides(const KDL::Chain& chain) {
  KDL::Chain out;
  out.addSegment(KDL::Segment("gravity_x", KDL::Joint("gravity_x", KDL::Joint::TransX)));
  out.addSegment(KDL::Segment("gravity_y", KDL::Joint("gravity_y", KDL::Joint::TransY)));
  out.addSegment(KDL::Segment("gravity_z", KDL::Joint("gravity_z", KDL::Joint::TransZ)));
  out.addChain(chain);
  return out;
}

}  // namespace

KdlParts::KdlParts(const KDL::Chain& kinematic_chain)
    : chain(kinematic_chain),
      dynamic_chain(with_base_slides(kinematic_chain)),
      fk(chain),
      jac(chain),
      rne(dynamic_chain, KDL::Vector::Zero()),
      dyn(chain, KDL::Vector::Zero()),
      q(chain.getNrOfJoints()),
      dq(dynamic_chain.getNrOfJoints()),
      dqd(dynamic_chain.getNrOfJoints()),
      dqdd(dynamic_chain.getNrOfJoints()),
      dtau(dynamic_chain.getNrOfJoints()),
      J(chain.getNrOfJoints()),
      H(chain.getNrOfJoints()),
      no_wrench(dynamic_chain.getNrOfSegments(), KDL::Wrench::Zero()),
      ldlt(static_cast<Eigen::Index>(chain.getNrOfJoints())) {}

}  // namespace detail

void ArmModel::build_kdl() {
  KDL::Chain chain;
  for (int j = 0; j < dof(); ++j) {
    const Joint& jt = joints_[static_cast<std::size_t>(j)];
    const std::string& name = joint_names_[static_cast<std::size_t>(j)];
    const Eigen::Vector3d axis = jt.body_T_origin.linear() * jt.axis;  // in the parent body's frame
    const KDL::Joint joint(name, detail::to_kdl(Eigen::Vector3d(jt.body_T_origin.translation())), detail::to_kdl(axis),
                           jt.kind == JointKind::kPrismatic ? KDL::Joint::TransAxis : KDL::Joint::RotAxis);
    const BodyInertia& b = bodies_[static_cast<std::size_t>(j + 1)];
    const Eigen::Matrix3d& I = b.inertia;
    const KDL::RigidBodyInertia inertia(b.mass, detail::to_kdl(b.com),
                                        KDL::RotationalInertia(I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)));
    chain.addSegment(KDL::Segment(name, joint, detail::to_kdl(jt.body_T_origin), inertia));
  }
  kdl_ = std::make_unique<detail::KdlParts>(chain);
}

}  // namespace wysiwyf::robot
