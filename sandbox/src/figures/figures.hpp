#pragma once
// `sandbox figures`: the paper's figures (Kenwright 2015) reproduced with our code. Each function
// renders one figure to a PNG in `out_dir` and returns its file name and a line on what it shows.
#include <string>
#include <vector>

namespace sandbox::figures {

struct Figure {
  std::string file;     ///< PNG file name inside the output folder
  std::string caption;  ///< what the picture shows, with the measured figures behind it
};

struct FigureOptions {
  std::string out_dir = "docs/figures";
  int panel_width = 640;  ///< pixels per panel
  int panel_height = 400;
  int samples = 4;  ///< MSAA
};

/// Figure "Vehicle Convex Hull": (a) the mesh, (b) its convex hull, (c) control meshes of decreasing
/// level of detail.
Figure convexHullFigure(const FigureOptions& options);

/// Figure "Control Point Weighting": one corner control point lifted; the mesh follows with alpha = 1..5.
Figure weightingFigure(const FigureOptions& options);

/// The drinks can and its control mesh.
Figure canFigure(const FigureOptions& options);

/// Figure "Direct Wall Collision": the wall_crash scene, the car coloured by permanent displacement.
Figure wallCrashFigure(const FigureOptions& options);

/// Figure "Mesh Deformation": a 900,000-vertex car with 60 control points after minor hits (post_bumps).
Figure minorHitsFigure(const FigureOptions& options);

/// Not the paper's: wall_crash embedded by the idw and the mls skin side by side (skin_figures.cpp).
Figure wallCrashSkinsFigure(const FigureOptions& options);

/// Not the paper's: the front profile after wall_crash with each skin, plotted (front_profile.hpp).
Figure frontProfileFigure(const FigureOptions& options);

}  // namespace sandbox::figures
