// The tools' progress line on stderr: "what [####......] done/total", ended by a newline when done.
#ifndef ENHANCED_ORB_TOOLS_PROGRESS_H
#define ENHANCED_ORB_TOOLS_PROGRESS_H

#include <iomanip>
#include <iostream>
#include <string>

namespace enhanced_orb::tools {

inline void progress(const std::string& what, size_t done, size_t total) {
  const int width = 30;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  std::cerr << "\r" << std::left << std::setw(22) << what << " [" << std::string(filled, '#')
            << std::string(width - filled, '.') << "] " << done << "/" << total << std::flush;
  if (done == total) {
    std::cerr << "\n";
  }
}

}  // namespace enhanced_orb::tools

#endif  // ENHANCED_ORB_TOOLS_PROGRESS_H
