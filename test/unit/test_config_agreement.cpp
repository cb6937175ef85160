// One source of truth: the nodelets' field lists name every cfg/*.cfg field once, and the
// dynamic_reconfigure defaults and ranges agree with the parameter table (Params(), validate()).
#include <cmath>
#include <fstream>
#include <iterator>
#include <regex>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include <gtest/gtest.h>

#include "config_fields.h"
#include "enhanced_orb/params.h"

using namespace enhanced_orb;

namespace {

// Whether validate() accepts `value` for the parameter `name`.
bool accepted(const std::string& name, const std::string& value) {
  Params p;
  EXPECT_EQ(setParam(p, name, value), "") << name << " = " << value;
  return validate(p).empty();
}

template <typename T>
void expectSameRange(const std::string& name, T lo, T hi) {
  EXPECT_TRUE(accepted(name, std::to_string(lo))) << name << " minimum " << lo;
  EXPECT_TRUE(accepted(name, std::to_string(hi))) << name << " maximum " << hi;
  if constexpr (std::is_integral_v<T>) {
    EXPECT_FALSE(accepted(name, std::to_string(lo - 1))) << name << " below " << lo;
    EXPECT_FALSE(accepted(name, std::to_string(hi + 1))) << name << " above " << hi;
  } else {
    EXPECT_FALSE(accepted(name, std::to_string(lo - 0.01))) << name << " below " << lo;
    EXPECT_FALSE(accepted(name, std::to_string(hi + 0.01))) << name << " above " << hi;
  }
}

}  // namespace

namespace {

// The names a cfg file gives gen.add().
std::set<std::string> cfgNames(const std::string& file) {
  std::ifstream in(std::string(ENHANCED_ORB_SOURCE_DIR) + "/cfg/" + file);
  EXPECT_TRUE(in.good()) << file;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::regex add(R"re(gen\.add\("(\w+)")re");
  std::set<std::string> names;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), add); it != std::sregex_iterator(); ++it) {
    names.insert((*it)[1]);
  }
  return names;
}

template <class ConfigT>
std::set<std::string> fieldNames(const std::vector<ConfigField<ConfigT>>& fields) {
  std::set<std::string> names;
  for (const auto& f : fields) {
    EXPECT_TRUE(names.insert(f.name).second) << f.name << " listed twice";
  }
  return names;
}

bool inTable(const std::string& name) {
  return paramText(Params(), name).has_value();
}

// Each field of the table: its cfg default is the default mode's value.
template <class ConfigT>
void expectDefaultsOfTheDefaultMode(const std::vector<ConfigField<ConfigT>>& fields) {
  const ConfigT config = ConfigT::__getDefault__();
  for (const auto& f : fields) {
    if (!inTable(f.name)) {
      continue;
    }
    Params p;
    ASSERT_EQ(setParam(p, f.name, f.text(config)), "") << f.name;
    EXPECT_EQ(paramText(p, f.name), paramText(Params(), f.name))
        << f.name << ": the cfg default is not the default mode's";
  }
}

// Each numeric field of the table: the cfg's minimum and maximum are accepted, just outside refused.
template <class ConfigT>
void expectRangesOfTheLibrary(const std::vector<ConfigField<ConfigT>>& fields) {
  const ConfigT lo = ConfigT::__getMin__(), hi = ConfigT::__getMax__();
  int checked = 0;
  for (const auto& f : fields) {
    if (!inTable(f.name)) {
      continue;
    }
    if (std::holds_alternative<int ConfigT::*>(f.member)) {
      const auto m = std::get<int ConfigT::*>(f.member);
      expectSameRange(f.name, lo.*m, hi.*m);
      ++checked;
    } else if (std::holds_alternative<double ConfigT::*>(f.member)) {
      const auto m = std::get<double ConfigT::*>(f.member);
      expectSameRange(f.name, lo.*m, hi.*m);
      ++checked;
    }
  }
  EXPECT_GT(checked, 5);
}

}  // namespace

TEST(ConfigAgreement, TheNodeletsListEveryCfgFieldOnce) {
  EXPECT_EQ(fieldNames(enhanceConfigFields()), cfgNames("Enhance.cfg"));
  EXPECT_EQ(fieldNames(extractConfigFields()), cfgNames("Extract.cfg"));
}

TEST(ConfigAgreement, EveryParameterOfTheTableIsLive) {
  std::set<std::string> live = fieldNames(enhanceConfigFields());
  for (const std::string& name : fieldNames(extractConfigFields())) {
    // camera_motion only is both nodelets': each judges its stream's frames for its own settings.
    EXPECT_TRUE(live.insert(name).second || name == "camera_motion") << name << " is in both nodelets";
  }
  EXPECT_EQ(live.size(), fieldNames(enhanceConfigFields()).size() + fieldNames(extractConfigFields()).size() - 1);
  for (const std::string& name : paramNames()) {
    EXPECT_TRUE(live.count(name)) << name << " is in no nodelet's configuration";
  }
}

TEST(ConfigAgreement, DefaultsAreTheDefaultMode) {
  expectDefaultsOfTheDefaultMode(enhanceConfigFields());
  expectDefaultsOfTheDefaultMode(extractConfigFields());
}

TEST(ConfigAgreement, RangesAreTheLibrarys) {
  expectRangesOfTheLibrary(enhanceConfigFields());
  expectRangesOfTheLibrary(extractConfigFields());
}
