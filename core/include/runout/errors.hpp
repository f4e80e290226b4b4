// The error types runout raises. Each carries enough to tell the user what to change.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace runout {

// Bad input: names the source (file), the key and what is allowed.
class ConfigError : public std::runtime_error {
 public:
  ConfigError(std::string source, std::string key, const std::string& what)
      : std::runtime_error(source + ": " + key + ": " + what),
        source_(std::move(source)), key_(std::move(key)) {}
  const std::string& source() const { return source_; }
  const std::string& key() const { return key_; }

 private:
  std::string source_, key_;
};

// The integration went wrong (non-finite state, overlap beyond the guard): names the step, the
// time, the particle and the knob to change.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A bad command-line value (an option, a path to write to, a folder holding other results):
// the command exits 2 (README), naming the option.
class UsageError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// A file could not be read or written, or is corrupt.
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace runout
