// The fields of the nodelets' dynamic_reconfigure configurations (cfg/*.cfg), each named once:
// how ReconfigurableNodelet reads, copies and types them without dynamic_reconfigure's generated
// internals. test_config_agreement holds these lists to the cfg files and the parameter table.
#ifndef ENHANCED_ORB_CONFIG_FIELDS_H
#define ENHANCED_ORB_CONFIG_FIELDS_H

#include <iomanip>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "enhanced_orb/EnhanceConfig.h"
#include "enhanced_orb/ExtractConfig.h"

namespace enhanced_orb {

// One field of a configuration: its name (the cfg file's and, where it has one, the parameter
// table's) and where ConfigT keeps it.
template <class ConfigT>
struct ConfigField {
  using Member = std::variant<bool ConfigT::*, int ConfigT::*, double ConfigT::*, std::string ConfigT::*>;
  const char* name;
  Member member;

  // dynamic_reconfigure's name of the field's type: "bool", "int", "double" or "str".
  const char* type() const {
    static const char* const names[] = {"bool", "int", "double", "str"};
    return names[member.index()];
  }
  std::string text(const ConfigT& config) const {
    return std::visit(
        [&config](auto m) {
          std::ostringstream out;
          out << std::boolalpha << config.*m;
          if constexpr (std::is_same_v<decltype(m), double ConfigT::*>) {
            if (std::stod(out.str()) != config.*m) {  // the shortest text that reads back the same
              out.str("");
              out << std::setprecision(17) << config.*m;
            }
          }
          return out.str();
        },
        member);
  }
  void copy(const ConfigT& from, ConfigT& to) const {
    std::visit([&](auto m) { to.*m = from.*m; }, member);
  }
};

inline const std::vector<ConfigField<EnhanceConfig>>& enhanceConfigFields() {
  using C = EnhanceConfig;
  static const std::vector<ConfigField<C>> fields = {
      {"enhance", &C::enhance},
      {"tone_curve", &C::tone_curve},
      {"alpha", &C::alpha},
      {"tau", &C::tau},
      {"beta", &C::beta},
      {"sharpening", &C::sharpening},
      {"blur_ksize", &C::blur_ksize},
      {"blur_sigma", &C::blur_sigma},
      {"std_threshold", &C::std_threshold},
      {"gamma_mode", &C::gamma_mode},
      {"moving_gamma_mode", &C::moving_gamma_mode},
      {"camera_motion", &C::camera_motion},
      {"enhance_threads", &C::enhance_threads},
  };
  return fields;
}

inline const std::vector<ConfigField<ExtractConfig>>& extractConfigFields() {
  using C = ExtractConfig;
  static const std::vector<ConfigField<C>> fields = {
      {"threshold_mode", &C::threshold_mode},
      {"c_min", &C::c_min},
      {"threshold_scale", &C::threshold_scale},
      {"moving_threshold_scale", &C::moving_threshold_scale},
      {"grid_size", &C::grid_size},
      {"fast_threshold", &C::fast_threshold},
      {"max_features", &C::max_features},
      {"candidate_ratio", &C::candidate_ratio},
      {"noise_floor", &C::noise_floor},
      {"moving_noise_floor", &C::moving_noise_floor},
      {"floor_candidate_ratio", &C::floor_candidate_ratio},
      {"camera_motion", &C::camera_motion},
      {"n_levels", &C::n_levels},
      {"scale_factor", &C::scale_factor},
      {"threads", &C::threads},
      {"draw_keypoints", &C::draw_keypoints},
      {"draw_orientation", &C::draw_orientation},
      {"draw_max", &C::draw_max},
      {"draw_grid", &C::draw_grid},
      {"draw_text", &C::draw_text},
  };
  return fields;
}

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_CONFIG_FIELDS_H
