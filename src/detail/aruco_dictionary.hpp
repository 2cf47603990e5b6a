#pragma once
// The OpenCV dictionary of a target.yaml `markers.dictionary` name. Private:
// OpenCV stays out of the public headers (STYLE.md); the simulator draws the
// markers and the mono detector finds them with the same dictionary.

#include <l2s/error.hpp>

#include <opencv2/aruco.hpp>

#include <string>
#include <utility>

namespace l2s::detail {

inline cv::Ptr<cv::aruco::Dictionary> aruco_dictionary(const std::string& name) {
  using cv::aruco::PREDEFINED_DICTIONARY_NAME;
  static const std::pair<const char*, PREDEFINED_DICTIONARY_NAME> kNames[] = {
      {"DICT_4X4_50", cv::aruco::DICT_4X4_50},     {"DICT_4X4_100", cv::aruco::DICT_4X4_100},
      {"DICT_4X4_250", cv::aruco::DICT_4X4_250},   {"DICT_4X4_1000", cv::aruco::DICT_4X4_1000},
      {"DICT_5X5_50", cv::aruco::DICT_5X5_50},     {"DICT_5X5_100", cv::aruco::DICT_5X5_100},
      {"DICT_5X5_250", cv::aruco::DICT_5X5_250},   {"DICT_5X5_1000", cv::aruco::DICT_5X5_1000},
      {"DICT_6X6_50", cv::aruco::DICT_6X6_50},     {"DICT_6X6_100", cv::aruco::DICT_6X6_100},
      {"DICT_6X6_250", cv::aruco::DICT_6X6_250},   {"DICT_6X6_1000", cv::aruco::DICT_6X6_1000},
      {"DICT_7X7_50", cv::aruco::DICT_7X7_50},     {"DICT_7X7_100", cv::aruco::DICT_7X7_100},
      {"DICT_7X7_250", cv::aruco::DICT_7X7_250},   {"DICT_7X7_1000", cv::aruco::DICT_7X7_1000},
      {"DICT_ARUCO_ORIGINAL", cv::aruco::DICT_ARUCO_ORIGINAL}};
  for (const auto& [key, value] : kNames)
    if (name == key) return cv::aruco::getPredefinedDictionary(value);
  throw ParamError("markers.dictionary", "unknown ArUco dictionary '" + name + "'");
}

}  // namespace l2s::detail
