#include "lagrange/model.hpp"

namespace lagrange {

void Body::make_free() {
  free = true;
  const char* axes[3] = {"x", "y", "z"};
  for (size_t k = 0; k < 3; ++k) {
    r[k] = GiNaC::symbol(name + "." + axes[k]);
    rd[k] = GiNaC::symbol(name + ".v" + axes[k]);
    rdd[k] = GiNaC::symbol(name + ".a" + axes[k]);
    w[k] = GiNaC::symbol(name + ".w" + axes[k]);
    wd[k] = GiNaC::symbol(name + ".w" + axes[k] + "_dot");
  }
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j)
      R[3 * i + j] = GiNaC::symbol(name + ".R" + std::to_string(i + 1) + std::to_string(j + 1));
}

Vec3 Body::origin() const {
  return free ? Vec3{r[0], r[1], r[2]} : position;
}

Mat3 Body::rot() const {
  if (!free) return rotation;
  Mat3 m;
  for (size_t i = 0; i < 3; ++i)
    for (size_t j = 0; j < 3; ++j) m[i][j] = R[3 * i + j];
  return m;
}

Vec3 Body::world_point(const Vec3& p) const {
  const Vec3 o = origin();
  const Mat3 m = rot();
  Vec3 x;
  for (size_t i = 0; i < 3; ++i) x[i] = o[i] + m[i][0] * p[0] + m[i][1] * p[1] + m[i][2] * p[2];
  return x;
}

}  // namespace lagrange
