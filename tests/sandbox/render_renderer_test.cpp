// The renderer draws what the camera sees where the camera says: a box's silhouette is the projection
// of its corners, a built-in car fills the screen rectangle its bounding box projects to.
#include <catch2/catch.hpp>

#include <deform/builtin_meshes.hpp>
#include <deform/mesh_import.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numbers>
#include <vector>

#include "render/frame_output.hpp"
#include "render/renderer.hpp"
#include "render/vehicle_meshes.hpp"
#include "render_test_support.hpp"

using namespace sandbox::render;
namespace fs = std::filesystem;

namespace {

constexpr int kWidth = 320, kHeight = 180;

// A plain black background and no ground, so every non-black pixel belongs to the object.
Environment plainEnvironment() {
  Environment environment;
  environment.sky = false;
  environment.background = Eigen::Vector3f::Zero();
  environment.ground.visible = false;
  return environment;
}

std::vector<Eigen::Vector2f> projectedCorners(const Camera& camera, const deform::Aabb& box) {
  std::vector<Eigen::Vector2f> corners;
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d p((c & 1) ? box.max_m.x() : box.min_m.x(), (c & 2) ? box.max_m.y() : box.min_m.y(),
                            (c & 4) ? box.max_m.z() : box.min_m.z());
    corners.push_back(projectToPixel(camera, p.cast<float>(), kWidth, kHeight).head<2>());
  }
  return corners;
}

// Convex hull (Andrew's monotone chain), counter-clockwise.
std::vector<Eigen::Vector2f> convexHull2d(std::vector<Eigen::Vector2f> points) {
  std::sort(points.begin(), points.end(),
            [](const auto& a, const auto& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  const auto cross = [](const Eigen::Vector2f& o, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
    return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
  };
  std::vector<Eigen::Vector2f> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// Area and area centroid of a simple polygon.
std::pair<float, Eigen::Vector2f> polygonAreaCentroid(const std::vector<Eigen::Vector2f>& polygon) {
  double area = 0;
  Eigen::Vector2d centroid(0, 0);
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Eigen::Vector2d a = polygon[i].cast<double>(), b = polygon[(i + 1) % polygon.size()].cast<double>();
    const double w = a.x() * b.y() - b.x() * a.y();
    area += w;
    centroid += (a + b) * w;
  }
  return {static_cast<float>(std::abs(area) / 2), (centroid / (3.0 * area)).cast<float>()};
}

}  // namespace

TEST_CASE("a rendered box covers exactly the projection of its corners", "[render]") {
  const deform::Mesh box_mesh = deform::makeBox({2.0, 1.0, 0.8}, 600);
  const deform::Aabb box = deform::boundingBox(box_mesh);
  Renderer renderer({kWidth, kHeight, 4});
  MeshData data = meshData(box_mesh, {0.7f, 0.7f, 0.7f});
  renderer.addMesh(data);
  Camera camera;
  camera.eye_m = {4.0f, -3.5f, 2.5f};
  camera.target_m = {0.3f, 0.2f, 0.0f};
  camera.fov_y_deg = 40.0f;

  const Image image = renderer.renderImage(camera, plainEnvironment());
  REQUIRE(image.width == kWidth);
  REQUIRE(image.height == kHeight);
  const render_test::Silhouette s = render_test::silhouette(image, Eigen::Vector3i::Zero());

  const std::vector<Eigen::Vector2f> outline = convexHull2d(projectedCorners(camera, box));
  const auto [area, centroid] = polygonAreaCentroid(outline);
  Eigen::Vector2f low = outline.front(), high = outline.front();
  for (const auto& p : outline) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  INFO("expected area " << area << " px, centroid " << centroid.transpose() << ", extent " << low.transpose()
                        << " .. " << high.transpose());
  INFO("drawn " << s.count << " px, centroid " << s.centroid.transpose() << ", extent " << s.min.transpose()
                << " .. " << s.max.transpose());
  REQUIRE(area > 2000.0f);  // the test means something only if the box is big on screen
  CHECK(static_cast<float>(s.count) == Approx(area).epsilon(0.03));
  CHECK((s.centroid - centroid).norm() < 1.0f);
  // Pixel centres of the outermost covered pixels lie within a pixel of the true outline.
  CHECK((s.min - low).cwiseAbs().maxCoeff() < 1.5f);
  CHECK((s.max - high).cwiseAbs().maxCoeff() < 1.5f);
}

TEST_CASE("a built-in sedan fills the screen rectangle its bounding box projects to", "[render]") {
  const deform::VehicleModel model = deform::loadVehicleModel("builtin:sedan?vertices=5000");
  Renderer renderer({kWidth, kHeight, 4});
  for (const MeshData& mesh : vehicleMeshes(model)) renderer.addMesh(mesh);
  const deform::Aabb box = vehicleBounds(model);
  // From the side the box is tight on the car: bumper to bumper, tyre bottom to roof.
  const Camera camera = presetCamera("side", box, renderer.aspect());

  const Image image = renderer.renderImage(camera, plainEnvironment());
  const render_test::Silhouette s = render_test::silhouette(image, Eigen::Vector3i::Zero());
  Eigen::Vector2f low = Eigen::Vector2f::Constant(1e9f), high = Eigen::Vector2f::Constant(-1e9f);
  for (const auto& p : projectedCorners(camera, box)) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  INFO("box projects to " << low.transpose() << " .. " << high.transpose() << "; car drawn "
                          << s.min.transpose() << " .. " << s.max.transpose() << ", " << s.count << " px");
  // Not blank: the car covers a good part of the frame.
  CHECK(s.count > static_cast<std::size_t>(kWidth * kHeight / 8));
  // Inside the box's projection...
  CHECK(s.min.x() >= low.x() - 1.0f);
  CHECK(s.min.y() >= low.y() - 1.0f);
  CHECK(s.max.x() <= high.x() + 1.0f);
  CHECK(s.max.y() <= high.y() + 1.0f);
  // ...and reaching its sides.
  CHECK(s.max.x() - s.min.x() > 0.9f * (high.x() - low.x()));
  CHECK(s.max.y() - s.min.y() > 0.75f * (high.y() - low.y()));
  // The framing keeps the car in the middle of the picture.
  CHECK(std::abs(0.5f * (s.min.x() + s.max.x()) - kWidth / 2.0f) < 0.1f * kWidth);
  CHECK(std::abs(0.5f * (s.min.y() + s.max.y()) - kHeight / 2.0f) < 0.1f * kHeight);
}

TEST_CASE("a full scene (sky, ground, shadow) keeps the picture size and changes under updates", "[render]") {
  const deform::Mesh box_mesh = deform::makeBox({1.0, 1.0, 1.0}, 200);
  Renderer renderer({kWidth, kHeight, 0});
  const Renderer::MeshId id = renderer.addMesh(meshData(box_mesh, {0.2f, 0.4f, 0.9f}));
  const deform::Aabb box = deform::boundingBox(box_mesh);
  const Camera camera = presetCamera("side", box, renderer.aspect());
  const Image before = renderer.renderImage(camera, environmentAround(box));
  REQUIRE(before.rgba.size() == static_cast<std::size_t>(kWidth * kHeight * 4));

  // Move every vertex up by 0.3 m through the dynamic buffer: the picture must change.
  std::vector<Eigen::Vector3f> raised = box_mesh.positions_m;
  for (auto& p : raised) p.z() += 0.3f;
  renderer.updatePositions(id, raised);
  const Image after = renderer.renderImage(camera, environmentAround(box));
  std::size_t changed = 0;
  for (std::size_t i = 0; i < before.rgba.size(); ++i) changed += before.rgba[i] != after.rgba[i];
  CHECK(changed > before.rgba.size() / 50);
}

TEST_CASE("fitCamera keeps every corner of the box inside the picture margin", "[render]") {
  const deform::Aabb box{{-2.4, -0.9, -0.7}, {2.4, 0.9, 0.75}};
  for (const char* view : {"side", "chase", "front", "top", "quarter"}) {
    const Camera camera = presetCamera(view, box, 16.0f / 9.0f);
    float touches = 0.0f;  // how close the framing comes to the margin (1 = touches it)
    for (const auto& p : projectedCorners(camera, box)) {
      INFO(view << ": corner at " << p.transpose());
      CHECK(p.x() >= 0.07f * kWidth);
      CHECK(p.x() <= 0.93f * kWidth);
      CHECK(p.y() >= 0.07f * kHeight);
      CHECK(p.y() <= 0.93f * kHeight);
      touches = std::max(
          {touches, std::abs(p.x() / kWidth - 0.5f) / 0.42f, std::abs(p.y() / kHeight - 0.5f) / 0.42f});
    }
    CHECK(touches == Approx(1.0f).epsilon(0.02));  // fitted, not merely inside
  }
  CHECK_THROWS_WITH(presetCamera("fisheye", box, 1.0f), Catch::Contains("--camera"));
}

TEST_CASE("rendered frames become PNGs and an MP4 through FrameOutput", "[render]") {
  const fs::path dir = render_test::scratchDir("render_frames_test");
  const deform::VehicleModel model = deform::loadVehicleModel("builtin:sedan?vertices=3000");
  Renderer renderer({kWidth, kHeight, 0});
  for (const MeshData& mesh : vehicleMeshes(model)) renderer.addMesh(mesh);
  const deform::Aabb box = vehicleBounds(model);
  const bool video = VideoWriter::available("ffmpeg") && VideoWriter::available("ffprobe");
  if (!video) WARN("ffmpeg or ffprobe is not installed: only PNG frames are checked");
  FrameOutputSettings settings;
  settings.png_folder = dir.string();
  if (video) settings.video_path = (dir / "video.mp4").string();
  settings.video = {kWidth, kHeight, 25.0};
  FrameOutput output(settings);
  constexpr int kFrames = 4;
  for (int i = 0; i < kFrames; ++i) {
    // The car drives 0.5 m forward per frame under a chase camera.
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(0.5 * i, 0.0, 0.0);
    Eigen::Matrix4f model_matrix = Eigen::Matrix4f::Identity();
    model_matrix(0, 3) = static_cast<float>(pose.translation().x());
    // Mesh 0 is the body, then one per wheel: all move with the car.
    REQUIRE(vehicleMeshes(model).size() == 1 + model.wheels.size());
    for (Renderer::MeshId id = 0; id < 1 + model.wheels.size(); ++id) {
      Eigen::Matrix4f placed = model_matrix;
      if (id > 0) placed.block<3, 1>(0, 3) += model.wheels[id - 1].centre_m.cast<float>();
      renderer.setTransform(id, placed);
    }
    output.add(renderer.renderImage(chaseCamera(pose, 7.0, 2.5), environmentAround(box)));
  }
  output.finish();
  for (int i = 0; i < kFrames; ++i) {
    const Image frame = readPng(output.pngPath(i));
    CHECK(frame.width == kWidth);
    CHECK(frame.height == kHeight);
  }
  if (video) {
    FILE* pipe =
        popen(("ffprobe -v error -count_frames -select_streams v:0 -show_entries stream=nb_read_frames "
               "-of csv=p=0 " +
               shellQuote(settings.video_path))
                  .c_str(),
              "r");
    char buffer[64] = {};
    REQUIRE(pipe != nullptr);
    const bool read = std::fgets(buffer, sizeof buffer, pipe) != nullptr;
    pclose(pipe);
    REQUIRE(read);
    CHECK(std::atoi(buffer) == kFrames);
  }
  CHECK_THROWS_WITH(FrameOutput({(dir / "missing").string(), "", {}}), Catch::Contains("missing"));
  fs::remove_all(dir);
}

TEST_CASE("chaseCamera sits behind and above the car along its heading", "[render]") {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(100.0, -20.0, 0.7);
  // Heading +Y (yawed 90 degrees left) and pitched a little: the camera ignores the pitch.
  pose.linear() = (Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()) *
                   Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitY()))
                      .toRotationMatrix();
  const Camera camera = chaseCamera(pose, 9.0, 3.0);
  CHECK(camera.eye_m.x() == Approx(100.0f).margin(1e-3));
  CHECK(camera.eye_m.y() == Approx(-29.0f).margin(1e-3));
  CHECK(camera.eye_m.z() == Approx(3.7f).margin(1e-3));
  CHECK(camera.target_m.y() > -20.0f);  // looks ahead of the car
  // The car's centre projects onto the picture's vertical centre line.
  const Eigen::Vector3f pixel = projectToPixel(camera, pose.translation().cast<float>(), kWidth, kHeight);
  CHECK(pixel.x() == Approx(kWidth / 2.0f).margin(0.5));
  CHECK(pixel.z() > 0.0f);
}
