#pragma once
// The error family of l2scalib. Invalid input or configuration throws one of
// these; expected failures (no board in a frame) are statuses in results.
// Every class here may be caught as l2s::Error (or std::runtime_error); all
// are exported, so that a program catches what a shared library throws.

#include <l2s/export.hpp>

#include <cassert>
#include <stdexcept>
#include <string>

namespace l2s {

/// Base of every exception the library throws.
class L2S_EXPORT Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A file that is missing, unreadable or does not follow DATASET.md.
/// The message always starts with the file's path.
class L2S_EXPORT FileError : public Error {
 public:
  FileError(const std::string& path, const std::string& problem)
      : Error(path + ": " + problem), path_(path) {}
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// A parameter outside its valid range; the message names the field.
class L2S_EXPORT ParamError : public Error {
 public:
  ParamError(const std::string& field, const std::string& problem)
      : Error("parameter " + field + ": " + problem), field_(field), problem_(problem) {}
  const std::string& field() const { return field_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string field_;
  std::string problem_;
};

/// Data handed to a function that cannot be used: an image that does not fit
/// its camera, a calibration result that failed. The message starts with the
/// input's name ("left image: ...", "result: ...").
class L2S_EXPORT InputError : public Error {
 public:
  InputError(const std::string& input, const std::string& problem)
      : Error(input + ": " + problem), input_(input) {}
  const std::string& input() const { return input_; }

 private:
  std::string input_;
};

}  // namespace l2s

/// Internal invariant; compiled out in release builds.
#define L2S_ASSERT(condition) assert(condition)
