#pragma once
// A control mesh drawn as facets: every triangle gets its own three vertices and its face normal, so
// the coarse surface reads as the polyhedron it is.
#include <deform/control_mesh.hpp>
#include <deform/mesh.hpp>

namespace sandbox::figures {

deform::Mesh facetedMesh(const deform::ControlMesh& control);

}  // namespace sandbox::figures
