#pragma once
// A small command-line reader for the example programs: `--name value` options with
// defaults, typed access, and an error naming any unknown or malformed option.

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace growshell::examples {

class CommandLine {
 public:
  CommandLine(int argc, char** argv) {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      if (arg == "--help" || arg == "-h") {
        help_ = true;
        continue;
      }
      if (arg.rfind("--", 0) != 0) throw std::invalid_argument("unexpected argument '" + arg + "'");
      if (i + 1 >= argc) throw std::invalid_argument("option " + arg + " needs a value");
      values_[arg] = argv[++i];
    }
  }

  bool help() const { return help_; }

  double number(const std::string& name, double fallback) {
    used_.insert(name);
    const auto it = values_.find(name);
    if (it == values_.end()) return fallback;
    char* end = nullptr;
    const double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0')
      throw std::invalid_argument("option " + name + " expects a number, got '" + it->second + "'");
    return v;
  }

  int integer(const std::string& name, int fallback) {
    const double v = number(name, fallback);
    if (v != static_cast<int>(v))
      throw std::invalid_argument("option " + name + " expects an integer");
    return static_cast<int>(v);
  }

  std::string text(const std::string& name, const std::string& fallback) {
    used_.insert(name);
    const auto it = values_.find(name);
    return it == values_.end() ? fallback : it->second;
  }

  /// A comma-separated list of finite numbers (e.g. --h 0.04,0.02), `fallback` if the option
  /// is absent; throws naming the option for an item that is not one, or for an empty list.
  /// The caller checks the range.
  std::vector<double> number_list(const std::string& name, const std::string& fallback) {
    std::vector<double> values;
    std::stringstream in(text(name, fallback));
    std::string item;
    while (std::getline(in, item, ',')) {
      char* end = nullptr;
      const double v = std::strtod(item.c_str(), &end);
      if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
        throw std::invalid_argument("option " + name + ": '" + item + "' is not a number");
      values.push_back(v);
    }
    if (values.empty()) throw std::invalid_argument("option " + name + " lists no number");
    return values;
  }

  /// Throws naming the first option that no accessor asked for.
  void reject_unknown() const {
    for (const auto& [name, value] : values_)
      if (!used_.count(name)) throw std::invalid_argument("unknown option " + name);
  }

 private:
  std::map<std::string, std::string> values_;
  std::set<std::string> used_;
  bool help_ = false;
};

}  // namespace growshell::examples
