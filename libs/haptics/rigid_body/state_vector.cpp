#include "rigid_body/state_vector.hpp"

namespace wysiwyf::haptics {

void pack_state(const std::vector<BodyState>& states, const std::vector<int>& dynamic, double* y) {
  for (std::size_t k = 0; k < dynamic.size(); ++k) {
    const BodyState& s = states[dynamic[k]];
    double* o = y + kStateSize * k;
    o[0] = s.x.x(), o[1] = s.x.y(), o[2] = s.x.z();
    o[3] = s.q.w(), o[4] = s.q.x(), o[5] = s.q.y(), o[6] = s.q.z();
    o[7] = s.P.x(), o[8] = s.P.y(), o[9] = s.P.z();
    o[10] = s.L.x(), o[11] = s.L.y(), o[12] = s.L.z();
  }
}

void unpack_state(const double* y, const std::vector<int>& dynamic, std::vector<BodyState>& states) {
  for (std::size_t k = 0; k < dynamic.size(); ++k) states[dynamic[k]] = unpack_body(y + kStateSize * k);
}

}  // namespace wysiwyf::haptics
