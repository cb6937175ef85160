// enhanced_orb_compare --paper: the experiments of ALGORITHM.md section 4 (the paper's Tables 2-4,
// Figures 6-7) on one input, for scripts/report.py paper.
#ifndef ENHANCED_ORB_TOOLS_PAPER_EXPERIMENTS_H
#define ENHANCED_ORB_TOOLS_PAPER_EXPERIMENTS_H

#include <string>
#include <vector>

namespace enhanced_orb::tools {

struct PaperOptions {
  // The input: one of a EuRoC sequence (ASL layout; frame pairs judged by its poses), a folder of
  // images in name order, or a bag's sensor_msgs/Image topic.
  std::string euroc, images, bag, topic;
  std::string output;
  int every = 10;      // photometric changes of every N-th frame
  int pair_every = 5;  // frame pairs start every N-th frame
  int max_frames = 0;  // at most this many frames; 0: all
  std::vector<int> steps{1, 5, 10};
  std::vector<int> budgets{0, 1000};  // 0: every corner
};

// Writes frames.csv, table2.csv, figure6.csv, pairs.csv and meta.csv under o.output, all renamed into
// place together at the end. Returns the exit code: 0 done, 1 no usable frame. Throws on an input
// or output that cannot be read or written.
int runPaperExperiments(const PaperOptions& o);

}  // namespace enhanced_orb::tools

#endif  // ENHANCED_ORB_TOOLS_PAPER_EXPERIMENTS_H
