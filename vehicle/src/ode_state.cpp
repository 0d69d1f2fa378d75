// ODE state saved and put back bit for bit (ode_support.hpp): body motion, orientations ODE's own
// normalisation keeps, and the order of a space's geoms.
#include "ode_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

namespace vehicle::ode {
namespace {

bool sameQuaternion(const dReal* a, const dReal* b) {
  return std::memcmp(a, b, 4 * sizeof(dReal)) == 0;
}

double nudged(double value, int ulps) {
  for (; ulps > 0; --ulps) value = std::nextafter(value, std::numeric_limits<double>::infinity());
  for (; ulps < 0; ++ulps) value = std::nextafter(value, -std::numeric_limits<double>::infinity());
  return value;
}

/// Nudges of the four components by up to 3 units in the last place, smallest total first.
const std::vector<std::array<int, 4>>& nudges() {
  static const std::vector<std::array<int, 4>> list = [] {
    std::vector<std::array<int, 4>> out;
    for (int a = -3; a <= 3; ++a)
      for (int b = -3; b <= 3; ++b)
        for (int c = -3; c <= 3; ++c)
          for (int d = -3; d <= 3; ++d)
            if (a != 0 || b != 0 || c != 0 || d != 0) out.push_back({a, b, c, d});
    std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) {
      return std::abs(x[0]) + std::abs(x[1]) + std::abs(x[2]) + std::abs(x[3]) <
             std::abs(y[0]) + std::abs(y[1]) + std::abs(y[2]) + std::abs(y[3]);
    });
    return out;
  }();
  return list;
}

/// Marks `geom` moved (dirty, to the front of its space's list) without changing where it is.
void markMoved(dGeomID geom) {
  if (dBodyID body = dGeomGetBody(geom)) {
    dGeomSetBody(geom, body);  // the same body: only dGeomMoved
  } else if (dGeomGetClass(geom) == dPlaneClass) {
    dVector4 p;
    dGeomPlaneGetParams(geom, p);
    dGeomPlaneSetParams(geom, p[0], p[1], p[2], p[3]);
  } else {
    const dReal* at = dGeomGetPosition(geom);
    const dReal x = at[0], y = at[1], z = at[2];
    dGeomSetPosition(geom, x, y, z);
  }
}

void ignorePair(void*, dGeomID, dGeomID) {}

}  // namespace

void keepOrientationRestorable(dBodyID body) {
  dQuaternion q;
  std::memcpy(q, dBodyGetQuaternion(body), sizeof q);
  dBodySetQuaternion(body, q);
  if (sameQuaternion(q, dBodyGetQuaternion(body))) return;
  for (const auto& n : nudges()) {
    dQuaternion t;
    for (int i = 0; i < 4; ++i) t[i] = nudged(q[i], n[static_cast<std::size_t>(i)]);
    dBodySetQuaternion(body, t);
    if (sameQuaternion(t, dBodyGetQuaternion(body))) return;
  }
  dBodySetQuaternion(body, q);  // none within reach (not met in 3e5 random steps): ODE's own
}

void saveBody(StateWriter& out, dBodyID body) {
  out.raw(dBodyGetPosition(body), 3 * sizeof(dReal));
  out.raw(dBodyGetQuaternion(body), 4 * sizeof(dReal));
  out.raw(dBodyGetLinearVel(body), 3 * sizeof(dReal));
  out.raw(dBodyGetAngularVel(body), 3 * sizeof(dReal));
  out.flag(dBodyIsEnabled(body) != 0);
}

void restoreBody(StateReader& in, dBodyID body, const char* what) {
  dReal p[3], q[4], v[3], w[3];
  in.raw(p, sizeof p);
  in.raw(q, sizeof q);
  in.raw(v, sizeof v);
  in.raw(w, sizeof w);
  const bool enabled = in.flag();
  for (double x : p) in.expect(std::isfinite(x), std::string(what) + ": position not finite");
  dBodySetPosition(body, p[0], p[1], p[2]);
  dBodySetQuaternion(body, q);
  in.expect(sameQuaternion(q, dBodyGetQuaternion(body)),
            std::string(what) + ": orientation cannot be put back exactly (not a saved state)");
  dBodySetLinearVel(body, v[0], v[1], v[2]);
  dBodySetAngularVel(body, w[0], w[1], w[2]);
  if (enabled) {
    dBodyEnable(body);
  } else {
    dBodyDisable(body);
  }
}

void saveGeomOrder(StateWriter& out, dSpaceID space, const std::vector<dGeomID>& known, bool moving_only) {
  const int count = dSpaceGetNumGeoms(space);
  if (!moving_only) out.u64(static_cast<uint64_t>(count));
  for (int i = 0; i < count; ++i) {
    const dGeomID geom = dSpaceGetGeom(space, i);
    if (moving_only && dGeomGetBody(geom) == nullptr) continue;
    const auto at = std::find(known.begin(), known.end(), geom);
    out.u64(static_cast<uint64_t>(at - known.begin()));  // known.size(): unknown (caught on restore)
  }
}

void restoreGeomOrder(StateReader& in, dSpaceID space, const std::vector<dGeomID>& known) {
  const std::size_t count = in.count(8);
  in.expect(count == known.size() && static_cast<int>(count) == dSpaceGetNumGeoms(space),
            "geom count does not match the scene");
  std::vector<dGeomID> order;
  std::vector<char> seen(count, 0);
  for (std::size_t i = 0; i < count; ++i) {
    const uint64_t index = in.u64();
    in.expect(index < count && !seen[index], "geom order is not a permutation");
    seen[index] = 1;
    order.push_back(known[index]);
  }
  // Clean every geom, then move them to the front last first: the list ends in the saved order, all
  // dirty (their bounding boxes recomputed at the next collision pass, to the same values).
  dSpaceCollide(space, nullptr, &ignorePair);
  for (auto it = order.rbegin(); it != order.rend(); ++it) markMoved(*it);
  for (std::size_t i = 0; i < count; ++i)
    in.expect(dSpaceGetGeom(space, static_cast<int>(i)) == order[i], "geom order could not be put back");
}

}  // namespace vehicle::ode
