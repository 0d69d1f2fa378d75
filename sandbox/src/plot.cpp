#include "plot.hpp"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace sandbox {

bool runGnuplot(const std::string& script_path, const std::string& script) {
  {
    std::ofstream out(script_path);
    out << script;
    if (!out.flush()) throw std::runtime_error(script_path + ": cannot write");
  }
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::fprintf(stderr,
                 "sandbox: gnuplot not found, no plot drawn (apt-get install gnuplot-nox); script: %s\n",
                 script_path.c_str());
    return false;
  }
  const std::string command = "gnuplot '" + script_path + "' 2>&1";
  if (std::system(command.c_str()) != 0) throw std::runtime_error("gnuplot failed on " + script_path);
  return true;
}

std::string gnuplotQuoted(const std::string& text) {
  std::string out = "'";
  for (char ch : text) {
    if (ch == '\'') out += '\'';
    out += ch;
  }
  out += '\'';
  return out;
}

}  // namespace sandbox
