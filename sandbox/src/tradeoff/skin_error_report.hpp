#pragma once
// The skin-alone measurement (tradeoff/skin_error.hpp) written out: skin_error.csv (every row),
// skin_error.md (the target at N = 60, K = 8, the trend with N, K and alpha) and the plots
// skin_error_rms.png and skin_error_max.png (error against N per field, one line per method and K).
#include "tradeoff/skin_error.hpp"

#include <string>
#include <vector>

namespace sandbox {

/// CSV of every row (errors in mm).
std::string skinErrorCsv(const std::vector<SkinErrorRow>& rows);

/// Markdown tables; `command` is the command line that reproduces them.
std::string skinErrorMarkdown(const std::vector<SkinErrorRow>& rows, const std::string& command);

/// Writes skin_error.csv, skin_error.md and the plots into `dir`.
void writeSkinErrorReport(const std::vector<SkinErrorRow>& rows, const std::string& dir,
                          const std::string& command);

/// The row of `field`, `method`, target N, K and alpha, or nullptr.
const SkinErrorRow* findSkinErrorRow(const std::vector<SkinErrorRow>& rows, const std::string& field,
                                     const std::string& method, std::size_t target_points, std::size_t k,
                                     double alpha);

}  // namespace sandbox
