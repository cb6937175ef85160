// The live parameters of a nodelet, one dynamic_reconfigure configuration type ConfigT: the preset
// that seeds them, the checks every change goes through, and what is logged and kept when a value
// is refused. Shared by EnhanceNodelet and ExtractNodelet; it uses dynamic_reconfigure's Server
// only, and reads ConfigT through the field lists of config_fields.h.
#ifndef ENHANCED_ORB_RECONFIGURABLE_NODELET_H
#define ENHANCED_ORB_RECONFIGURABLE_NODELET_H

#include <exception>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <dynamic_reconfigure/server.h>
#include <boost/thread/recursive_mutex.hpp>

#include "config_fields.h"
#include "enhanced_orb/params.h"
#include "image_nodelet.h"

namespace enhanced_orb {

template <class ConfigT>
class ReconfigurableNodelet : public ImageNodelet {
protected:
  using Fields = std::vector<ConfigField<ConfigT>>;

  // Every field of ConfigT, each once: enhanceConfigFields() or extractConfigFields().
  virtual const Fields& configFields() const = 0;
  // The parameters a configuration starts from before its fields are set (fields that are not in
  // the parameter table, such as draw options, are read by apply()).
  virtual Params baseParams() const { return Params(); }
  // Corrects a value in place before the checks (with a warning); nothing by default.
  virtual void adjust(ConfigT& /*config*/) {}
  // Puts a checked configuration to use. May throw std::invalid_argument to refuse it as a whole.
  virtual void apply(const ConfigT& config, const Params& params) = 0;

  // From advertiseOutputs(): warns about wrongly typed parameters, gives every parameter the launch
  // file or YAML did not set the ~preset's value, and starts the dynamic_reconfigure server.
  void startReconfigure() {
    std::map<std::string, std::string> types;
    for (const auto& f : configFields()) {
      types[f.name] = f.type();
    }
    warnWrongTypes(types);
    const Params preset = Params::preset(readPreset());
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    for (const auto& f : configFields()) {
      const std::optional<std::string> text = paramText(preset, f.name);
      if (text && !pnh.hasParam(f.name)) {
        setTyped(f.name, f.type(), *text);
      }
    }
    server_ = std::make_unique<dynamic_reconfigure::Server<ConfigT>>(config_mutex_, pnh);
    server_->getConfigDefault(valid_);
    server_->setCallback([this](ConfigT& config, uint32_t) {
      try {
        reconfigure(config);
      } catch (const std::exception& e) {
        NODELET_ERROR("reconfiguration failed, keeping the previous parameters: %s", e.what());
        config = valid_;
      }
    });
  }

private:
  // The configuration's fields that are in the parameter table, set on baseParams(); setParam()'s
  // message for each field whose text the table does not read goes to `problems`.
  Params toParams(const ConfigT& config, std::vector<std::string>* problems = nullptr) const {
    Params p = baseParams();
    for (const auto& f : configFields()) {
      if (!paramText(p, f.name)) {
        continue;
      }
      const std::string error = setParam(p, f.name, f.text(config));
      if (!error.empty() && problems) {
        problems->push_back(error);
      }
    }
    return p;
  }

  std::map<std::string, std::string> values(const ConfigT& config) const {
    std::map<std::string, std::string> out;
    for (const auto& f : configFields()) {
      out[f.name] = f.text(config);
    }
    return out;
  }

  // A refused value is set back to the last valid one in `config`, which the server then reports:
  // what dynamic_reconfigure shows is what runs, and one bad value never blocks the others.
  void reconfigure(ConfigT& config) {
    adjust(config);
    std::vector<std::string> problems;
    for (const std::string& problem : validate(toParams(config, &problems))) {
      problems.push_back(problem);
    }
    for (const std::string& problem : problems) {  // each starts with the parameter's name
      const std::string name = problem.substr(0, problem.find(' '));
      std::string kept = "the previous value";
      for (const auto& f : configFields()) {
        if (name == f.name) {
          f.copy(valid_, config);
          kept = f.text(valid_);
        }
      }
      NODELET_WARN("%s; keeping %s", problem.c_str(), kept.c_str());
    }
    const Params p = toParams(config);
    try {
      const std::vector<std::string> still = validate(p);  // the restored values, invalid together
      if (!still.empty()) {
        throw std::invalid_argument(joinMessages(still));
      }
      apply(config, p);
    } catch (const std::invalid_argument& e) {
      NODELET_ERROR("parameters rejected, keeping the previous ones: %s", e.what());
      config = valid_;
      return;
    }
    warnInactive(p, values(config));
    valid_ = config;
  }

  boost::recursive_mutex config_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ConfigT>> server_;
  ConfigT valid_;  // the last configuration applied
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_RECONFIGURABLE_NODELET_H
