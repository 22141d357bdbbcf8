#pragma once
// Affine maps in double precision (3x3 linear part + translation): instance transforms, a box's
// node frame -> camera space, and the area and length scales they apply.
#include <cmath>
#include <glm/glm.hpp>

namespace lzb {

struct Affine {
  glm::dmat3 a{1.0};  // linear part (column-major, as glm)
  glm::dvec3 t{0.0};  // translation

  static Affine from(const glm::dmat4& m) { return {glm::dmat3(m), glm::dvec3(m[3])}; }
  glm::dmat4 matrix() const {
    glm::dmat4 m(a);
    m[3] = glm::dvec4(t, 1.0);
    return m;
  }
  glm::dvec3 point(const glm::dvec3& p) const { return a * p + t; }
  glm::dvec3 vector(const glm::dvec3& v) const { return a * v; }
  // this ∘ o: first o, then this.
  Affine operator*(const Affine& o) const { return {a * o.a, a * o.t + t}; }
  bool translationOnly() const { return a == glm::dmat3(1.0); }
  double det() const { return glm::determinant(a); }
};

// The rows of the camera's view basis as an affine map world -> camera space (x right, y up,
// z = view depth along forward): the depth convention of src/core/camera.hpp.
inline Affine worldToCamera(const glm::dvec3& eye, const glm::dvec3& right, const glm::dvec3& up,
                            const glm::dvec3& forward) {
  Affine m;
  m.a = glm::transpose(glm::dmat3(right, up, forward));
  m.t = -(m.a * eye);
  return m;
}

// Largest singular value of a (how much it can stretch a length).
double maxStretch(const glm::dmat3& a);
// sigma1 * sigma2 of a: the most it can scale the area of a surface element (the spectral norm
// of its cofactor matrix), so sampling by local area times this never undersamples.
double maxAreaScale(const glm::dmat3& a);

}  // namespace lzb
