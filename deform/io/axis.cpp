#include <deform/error.hpp>
#include <deform/mesh_import.hpp>

namespace deform {

Axis parseAxis(const std::string& text, const std::string& field) {
  std::string t = text;
  if (!t.empty() && t[0] == '+') t.erase(0, 1);
  if (t == "x" || t == "X") return Axis::PosX;
  if (t == "-x" || t == "-X") return Axis::NegX;
  if (t == "y" || t == "Y") return Axis::PosY;
  if (t == "-y" || t == "-Y") return Axis::NegY;
  if (t == "z" || t == "Z") return Axis::PosZ;
  if (t == "-z" || t == "-Z") return Axis::NegZ;
  throw InputError(field + ": '" + text + "' is not an axis (x, -x, y, -y, z, -z)");
}

}  // namespace deform
