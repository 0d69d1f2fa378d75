// File axes to the vehicle frame (DESIGN.md section 2: X forward, Y left, Z up).
#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

#include <Eigen/Geometry>
#include <cmath>

namespace deform {

std::string axisName(Axis axis) {
  switch (axis) {
    case Axis::PosX:
      return "+x";
    case Axis::NegX:
      return "-x";
    case Axis::PosY:
      return "+y";
    case Axis::NegY:
      return "-y";
    case Axis::PosZ:
      return "+z";
    case Axis::NegZ:
      return "-z";
  }
  return "?";
}

Eigen::Vector3d axisVector(Axis axis) {
  switch (axis) {
    case Axis::PosX:
      return Eigen::Vector3d::UnitX();
    case Axis::NegX:
      return -Eigen::Vector3d::UnitX();
    case Axis::PosY:
      return Eigen::Vector3d::UnitY();
    case Axis::NegY:
      return -Eigen::Vector3d::UnitY();
    case Axis::PosZ:
      return Eigen::Vector3d::UnitZ();
    case Axis::NegZ:
      return -Eigen::Vector3d::UnitZ();
  }
  return Eigen::Vector3d::UnitZ();
}

Eigen::Matrix3d vehicleFrameRotation(Axis up, Axis forward, const std::string& source) {
  const Eigen::Vector3d u = axisVector(up);
  const Eigen::Vector3d f = axisVector(forward);
  if (std::abs(u.dot(f)) > 0.5)
    throw InputError(source + ": up axis " + axisName(up) + " and forward axis " + axisName(forward) +
                     " must be perpendicular");
  // Rows are the file's forward, left and up: v_vehicle = (f.v, l.v, u.v). With l = u x f the rows form
  // a right-handed orthonormal basis (f x l = u), so the determinant is +1: a rotation, never a mirror.
  Eigen::Matrix3d r;
  r.row(0) = f.transpose();
  r.row(1) = u.cross(f).transpose();
  r.row(2) = u.transpose();
  return r;
}

}  // namespace deform
