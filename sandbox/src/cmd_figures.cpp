// `sandbox figures`: the paper's figures reproduced with our code, and docs/FIGURES.md beside them.
#include <cstdio>
#include <fstream>
#include <memory>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "figures/figures.hpp"

namespace sandbox {
namespace {

struct FiguresFlags {
  figures::FigureOptions options;
  std::string markdown = "docs/FIGURES.md";
};

/// The paper's own caption for each figure we reproduce (Kenwright 2015, first draft).
struct PaperFigure {
  const char* title;
  const char* paper_caption;
  figures::Figure (*make)(const figures::FigureOptions&);
};

const PaperFigure kFigures[] = {
    {"Vehicle Convex Hull",
     "Generating a convex hull mesh for the vehicle model. (a) original mesh, (b) convex hull for collisions "
     "and "
     "control points, and (c) different levels of detail for the deformation control model by reducing the "
     "convex "
     "hull triangles and hence number of control points.",
     figures::convexHullFigure},
    {"Control Point Weighting",
     "Example of the biasing influences of control points to different powers (a) alpha=1, (b) alpha=2, (c) "
     "alpha=3, (d) alpha=4, and (e) alpha=5. Increasing the inverse distance to the power means the control "
     "point "
     "only influences points within its region.",
     figures::weightingFigure},
    {"Control Points and Vertices (drinks can)",
     "The control points coordinate the deformation of the high-detail graphical mesh ... we also applied "
     "the "
     "concept to test models to emphasis particular characteristics (e.g., a drinks can).",
     figures::canFigure},
    {"Direct Wall Collision",
     "An example of a head on crash into a flat wall. We can visually see the spatial influence of the front "
     "deformation across the car's body. ... We can visualize the coupled influence of the deformation "
     "across the "
     "car using colors (i.e., red largest influence and blue no influence).",
     figures::wallCrashFigure},
    {"Mesh Deformation",
     "A vehicle with 900,000 vertices and 60 control points that has bumped into minor objects (e.g., posts "
     "and "
     "vegetation).",
     figures::minorHitsFigure},
    // Not the paper's (empty caption): what the skin adds to the picture.
    {"Wall crash front: idw against mls skin", "", figures::wallCrashSkinsFigure},
    {"Front profile after the wall crash", "", figures::frontProfileFigure},
};

void runFigures(const FiguresFlags& flags) {
  std::string md =
      "# The paper's figures, reproduced\n\nMade by `build/bin/sandbox figures --out " +
      flags.options.out_dir +
      "` from our own code and built-in meshes. Each figure stands beside the caption of the paper's draft "
      "(Kenwright 2015) and a caption of what ours shows, with the figures measured while making it.\n";
  for (const auto& f : kFigures) {
    const figures::Figure made = f.make(flags.options);
    std::printf("wrote %s/%s\n", flags.options.out_dir.c_str(), made.file.c_str());
    md += "\n## " + std::string(f.title) + "\n\n![" + f.title + "](figures/" + made.file + ")\n\n";
    if (*f.paper_caption) md += "**Paper:** " + std::string(f.paper_caption) + "\n\n";
    md += "**Ours:** " + made.caption + "\n";
  }
  if (!flags.markdown.empty()) {
    std::ofstream(flags.markdown) << md;
    std::printf("wrote %s\n", flags.markdown.c_str());
  }
}

}  // namespace

void registerFiguresCommand(CLI::App& app) {
  auto flags = std::make_shared<FiguresFlags>();
  auto* cmd = app.add_subcommand("figures", "Reproduce the paper's figures (PNG) and docs/FIGURES.md");
  cmd->add_option("--out", flags->options.out_dir, "Folder for the PNGs")->capture_default_str();
  cmd->add_option("--markdown", flags->markdown, "Markdown page to write (empty: none)")
      ->capture_default_str();
  cmd->add_option("--panel-width", flags->options.panel_width, "Pixels per panel")->capture_default_str();
  cmd->add_option("--panel-height", flags->options.panel_height, "Pixels per panel")->capture_default_str();
  cmd->callback([flags] { runFigures(*flags); });
}

}  // namespace sandbox
