#pragma once
// Plots through gnuplot (Debian's gnuplot-nox, pngcairo terminal): the measurement commands write their
// data and a gnuplot script beside the PNG, so a plot can be restyled and redrawn without re-measuring.
#include <string>

namespace sandbox {

/// Writes `script` to `script_path` and runs gnuplot on it (the script sets its own output PNG).
/// Returns false, with a message on stderr naming what to install, when gnuplot is not on the PATH;
/// throws std::runtime_error when gnuplot fails on the script.
bool runGnuplot(const std::string& script_path, const std::string& script);

/// `text` quoted for a gnuplot string ('...', quotes doubled).
std::string gnuplotQuoted(const std::string& text);

}  // namespace sandbox
