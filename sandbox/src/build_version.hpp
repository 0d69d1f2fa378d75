#pragma once
// The program's version: the project version and the git commit it was built from
// ("0.1.0+bbb37ca0a1b2", "-dirty" with uncommitted changes). Sweep plans and results carry it
// (sweep/sweep_plan.hpp), so a plan run by another build is noticed.

namespace sandbox {

/// "<project version>+<git describe>", fixed when the binary was built.
const char* buildVersion();

}  // namespace sandbox
