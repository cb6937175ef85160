// Trains an ORB vocabulary for ORB-SLAM3 with the DBoW2 it ships (k = 10, L = 5, TF-IDF, L1), from
// cv::ORB descriptors of every image under the folders given, and writes it in ORB-SLAM3's text
// format. For evaluation where the official ORBvoc.txt is not at hand; use the same file for every
// build compared.
//
//   train_vocabulary OUT.txt DIR [DIR ...]
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "DBoW2/FORB.h"
#include "DBoW2/TemplatedVocabulary.h"

namespace fs = std::filesystem;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::cerr << "usage: train_vocabulary OUT.txt DIR [DIR ...]\n";
    return 2;
  }
  std::vector<fs::path> images;
  for (int i = 2; i < argc; ++i) {
    for (const auto& entry : fs::recursive_directory_iterator(argv[i])) {
      std::string ext = entry.path().extension().string();
      std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
      if (entry.is_regular_file() && (ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".ppm")) {
        images.push_back(entry.path());
      }
    }
  }
  std::sort(images.begin(), images.end());
  cv::Ptr<cv::ORB> orb = cv::ORB::create(1000);
  std::vector<std::vector<cv::Mat>> features;
  size_t count = 0;
  for (const fs::path& path : images) {
    const cv::Mat gray = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    if (gray.empty()) {
      continue;
    }
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    orb->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
    std::vector<cv::Mat> rows;
    for (int r = 0; r < descriptors.rows; ++r) {
      rows.push_back(descriptors.row(r).clone());
    }
    count += rows.size();
    if (!rows.empty()) {
      features.push_back(std::move(rows));
    }
  }
  if (count < 10000) {
    std::cerr << "train_vocabulary: only " << count << " descriptors from " << images.size() << " images\n";
    return 1;
  }
  std::cerr << "train_vocabulary: " << count << " descriptors from " << features.size() << " images\n";
  DBoW2::TemplatedVocabulary<DBoW2::FORB::TDescriptor, DBoW2::FORB> vocabulary(10, 5, DBoW2::TF_IDF, DBoW2::L1_NORM);
  vocabulary.create(features);
  const std::string out = argv[1];
  const std::string tmp = out + ".tmp";
  vocabulary.saveToTextFile(tmp);
  // ORB-SLAM3's loadFromTextFile reads until eof and turns an empty last line into one more word
  // with an undefined descriptor: the file must not end with a newline.
  std::string text;
  {
    std::ifstream in(tmp, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  while (!text.empty() && text.back() == '\n') {
    text.pop_back();
  }
  std::ofstream(out, std::ios::binary) << text;
  std::remove(tmp.c_str());
  std::cerr << "train_vocabulary: " << vocabulary.size() << " words in " << out << "\n";
  return 0;
}
