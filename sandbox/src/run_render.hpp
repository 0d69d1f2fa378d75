#pragma once
// Drawing a scene run: every car (its body following the control points through the skin, coloured by
// displacement for the heat map; its wheels turning, steering and riding the suspension), the
// obstacles where the world has them now, from the scene's camera.
#include <scenes/car_skin.hpp>
#include <scenes/skin_obstacles.hpp>

#include <deform/skin.hpp>
#include <scenes/scene_run.hpp>

#include <memory>
#include <vector>

#include "render/renderer.hpp"

namespace sandbox {

/// The scene's camera for the world as it is now (chase, side or fixed; scenes/README.md).
render::Camera sceneCamera(const scenes::SceneRun& run);

/// Ground, lights and sky for the scene: the ground plane at z = 0 around the first car's start, its
/// grid and fade scaled to the car (a drinks can gets a centimetre grid).
render::Environment sceneEnvironment(const scenes::SceneRun& run);

class RunRenderer {
 public:
  /// Builds the renderer, the skins (timed as embed) and the meshes of cars and obstacles.
  RunRenderer(const scenes::SceneRun& run, const scenes::OutputConfig& outputs, scenes::StageTimes& times);
  ~RunRenderer();

  /// Embeds the render meshes for the control points now (embed time) and draws the frame (render time).
  render::Image frame(const scenes::SceneRun& run, scenes::StageTimes& times);
  /// frame() in its three steps, so that the last can run on another thread while the next frame draws:
  /// draw() embeds and submits the frame (the rasteriser may still be working when it returns);
  /// readback() waits for it and reads it; finishFrame() smooths its edges (any thread).
  void draw(const scenes::SceneRun& run, scenes::StageTimes& times);
  render::Image readback();
  void finishFrame(render::Image& image) const;
  render::Renderer& renderer() { return *renderer_; }

  /// Cars x frames whose embedding was skipped because the car was out of the camera's view.
  std::size_t embedsOutOfView() const { return embeds_out_of_view_; }

  /// The car's skinned body (vehicle frame) as of the last frame.
  const scenes::CarSkin& skin(std::size_t car) const { return *cars_[car].skin; }

 private:
  /// Car i's skins built again on its control points now (its body was refined).
  void rebind(const scenes::SceneRun& run, std::size_t i);
  struct CarMeshes {
    render::Renderer::MeshId body = 0;
    std::vector<render::Renderer::MeshId> wheels;
    std::unique_ptr<scenes::CarSkin> skin;
    scenes::SkinObstacles obstacles_near;  ///< scratch: what its render mesh is kept out of
    /// The wheel centres (vehicle frame) embedded like render vertices: a crushed front carries its
    /// wheels back with it instead of leaving them standing out of the bodywork.
    deform::Skin hub_skin;
    std::vector<Eigen::Vector3f> hub_rest_m;
    float full_scale_m = 0.25f;
  };
  struct ObstacleMesh {
    render::Renderer::MeshId mesh = 0;
    vehicle::ObstacleId id = 0;
  };
  std::unique_ptr<render::Renderer> renderer_;
  std::vector<CarMeshes> cars_;
  std::vector<ObstacleMesh> obstacles_;
  render::Environment environment_;
  bool heatmap_ = false;
  float aspect_ = 16.0f / 9.0f;  ///< picture width / height
  std::size_t embeds_out_of_view_ = 0;
};

/// How far the bodywork around each of `points_m` (vehicle frame, embedded in the control points by
/// `skin`) moved in the car's ground plane [m]: wheel hubs carried back by a crushed front.
std::vector<Eigen::Vector3d> embeddedShifts_m(const deform::Skin& skin,
                                              const std::vector<Eigen::Vector3f>& points_m,
                                              const std::vector<Eigen::Vector3d>& displacements_m);

/// The car's body deformed as it is now (vehicle frame), kept out of what it touches, without rendering:
/// for `sandbox export`.
deform::Mesh deformedBody(const scenes::SceneRun& run, std::size_t car);

}  // namespace sandbox
