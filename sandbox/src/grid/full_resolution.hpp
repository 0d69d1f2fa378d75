#pragma once
// Baseline: every render-mesh vertex a point mass, held by XPBD constraints along the mesh's edges (what
// node-beam games do), solved by our own solver with the same settings, so the comparison is of the model
// size alone.
#include "grid/bench_grid.hpp"
#include "step_cost.hpp"

#include <deform/mesh.hpp>

namespace sandbox {

/// Builds the full-resolution body of `mesh` (a closed surface: every edge shared by two triangles; equal
/// point masses summing to mass_kg; edges, a spoke per vertex to the centre so the shell keeps its
/// volume, bends across folded hinges) and times one step under the front wall.
GridRow fullResolutionRow(const deform::Mesh& mesh, double mass_kg, const StepCostOptions& step);

}  // namespace sandbox
