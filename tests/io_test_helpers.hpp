#pragma once
// Assertions shared by the io tests: an error must be a FileError that names
// the file (and, optionally, says what is wrong).

#include <l2s/error.hpp>

#include <gtest/gtest.h>

#include <string>

namespace l2s::test {

/// Success when `action` throws FileError whose path() is `path`, whose message
/// contains the path and, when given, `words`.
template <typename Action>
::testing::AssertionResult throws_file_error(Action&& action, const std::string& path,
                                             const std::string& words = "") {
  try {
    action();
  } catch (const FileError& e) {
    const std::string message = e.what();
    if (e.path() != path)
      return ::testing::AssertionFailure()
             << "FileError names '" << e.path() << "', expected '" << path << "': " << message;
    if (message.find(path) == std::string::npos || message.find(words) == std::string::npos)
      return ::testing::AssertionFailure() << "message lacks '" << words << "': " << message;
    return ::testing::AssertionSuccess() << message;
  } catch (const std::exception& e) {
    return ::testing::AssertionFailure() << "threw another exception: " << e.what();
  }
  return ::testing::AssertionFailure() << "did not throw";
}

}  // namespace l2s::test

/// EXPECT_FILE_ERROR(statement, path[, words]): `statement` throws a FileError naming `path`.
#define EXPECT_FILE_ERROR(statement, ...) \
  EXPECT_TRUE(::l2s::test::throws_file_error([&] { statement; }, __VA_ARGS__))
