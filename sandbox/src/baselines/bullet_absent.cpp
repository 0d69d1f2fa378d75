// The Bullet baseline in a build without Bullet (libbullet-dev not found when configuring; sandbox/
// CMakeLists.txt): `bench grid` and `bench step --peer bullet` stop with this message (exit 1), every
// other command is whole. The tests are built only with Bullet.
#include "baselines/bullet_peer.hpp"
#include "baselines/bullet_soft_body.hpp"
#include "commands.hpp"

namespace sandbox::baselines {
namespace {

[[noreturn]] void noBullet() {
  throw CommandFailure(
      "this build has no Bullet, the baseline of bench grid and bench step --peer bullet: install "
      "libbullet-dev (tools/setup.sh test) and build again");
}

}  // namespace

PeerStepCost bulletPeerStepCost(const deform::BodySettings&, double, uint32_t, uint32_t, std::size_t,
                                std::size_t, double) {
  noBullet();
}

SoftBodyCost bulletSoftBodyCost(const deform::Mesh&, double, int, int) {
  noBullet();
}

SoftBodyCrash bulletWallCrash(const deform::Mesh&, double, double, double, double) {
  noBullet();
}

}  // namespace sandbox::baselines
