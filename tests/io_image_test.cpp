// Image files: what read_image makes of each kind of PNG, write_png, to_gray.
#include <l2s/error.hpp>
#include <l2s/io/image_io.hpp>

#include "io_test_helpers.hpp"
#include "support/test_data.hpp"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

namespace l2s::io {
namespace {

Image pattern(int width, int height, int channels) {
  Image image(width, height, channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (int c = 0; c < channels; ++c)
        image.at(x, y, c) = static_cast<std::uint8_t>(x * 7 + y * 3 + c * 50);
  return image;
}

TEST(ImageIo, RoundTripsGrayAndBgrExactly) {
  test::TempDir dir;
  for (int channels : {1, 3}) {
    const Image image = pattern(37, 21, channels);
    write_png(dir.file("i.png"), image);
    const Image back = read_image(dir.file("i.png"));
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 21);
    EXPECT_EQ(back.channels, channels);
    EXPECT_EQ(back.pixels, image.pixels);
  }
}

TEST(ImageIo, WritesTheSameBytesTwiceAtAnyCompression) {
  test::TempDir dir;
  const Image image = pattern(64, 48, 3);
  for (int level : {0, 3, 9}) {
    write_png(dir.file("a.png"), image, level);
    write_png(dir.file("b.png"), image, level);
    EXPECT_EQ(test::read_bytes(dir.file("a.png")), test::read_bytes(dir.file("b.png")));
    EXPECT_EQ(read_image(dir.file("a.png")).pixels, image.pixels);
  }
  EXPECT_THROW(write_png(dir.file("c.png"), image, 10), ParamError);
}

TEST(ImageIo, ConvertsSixteenBitAndAlphaImagesToEightBit) {
  test::TempDir dir;
  cv::Mat deep(4, 5, CV_16UC1, cv::Scalar(65535));
  deep.at<std::uint16_t>(1, 2) = 257 * 100;
  deep.at<std::uint16_t>(0, 0) = 0;
  ASSERT_TRUE(cv::imwrite(dir.file("deep.png"), deep));
  const Image gray = read_image(dir.file("deep.png"));
  EXPECT_EQ(gray.channels, 1);
  EXPECT_EQ(gray.at(2, 1), 100);
  EXPECT_EQ(gray.at(0, 0), 0);
  EXPECT_EQ(gray.at(4, 3), 255);

  cv::Mat bgra(3, 2, CV_8UC4, cv::Scalar(10, 20, 30, 128));
  ASSERT_TRUE(cv::imwrite(dir.file("bgra.png"), bgra));
  const Image bgr = read_image(dir.file("bgra.png"));
  EXPECT_EQ(bgr.channels, 3);
  EXPECT_EQ(bgr.at(1, 2, 0), 10);
  EXPECT_EQ(bgr.at(1, 2, 1), 20);
  EXPECT_EQ(bgr.at(1, 2, 2), 30);

  cv::Mat deep_color(2, 2, CV_16UC3, cv::Scalar(0, 257 * 200, 65535));
  ASSERT_TRUE(cv::imwrite(dir.file("deep_color.png"), deep_color));
  const Image color = read_image(dir.file("deep_color.png"));
  EXPECT_EQ(color.channels, 3);
  EXPECT_EQ(color.at(0, 0, 1), 200);
  EXPECT_EQ(color.at(0, 0, 2), 255);
}

TEST(ImageIo, ToGrayUsesLuminance) {
  Image bgr(2, 1, 3);
  bgr.at(0, 0, 0) = 255;  // pure blue
  bgr.at(1, 0, 1) = 255;  // pure green
  const Image gray = to_gray(bgr);
  EXPECT_EQ(gray.channels, 1);
  EXPECT_EQ(gray.at(0, 0), 29);   // 0.114 * 255
  EXPECT_EQ(gray.at(1, 0), 150);  // 0.587 * 255
  EXPECT_EQ(to_gray(gray).pixels, gray.pixels);
}

TEST(ImageIo, MissingAndUndecodableFilesAreFileErrors) {
  test::TempDir dir;
  EXPECT_FILE_ERROR(read_image(dir.file("none.png")), dir.file("none.png"), "missing file");
  test::write_text(dir.file("bad.png"), "\x89PNG\r\n\x1a\n this is not really a PNG");
  EXPECT_FILE_ERROR(read_image(dir.file("bad.png")), dir.file("bad.png"), "cannot decode");
  test::write_text(dir.file("empty.png"), "");
  EXPECT_FILE_ERROR(read_image(dir.file("empty.png")), dir.file("empty.png"));
}

TEST(ImageIo, RejectsImagesWhosePixelsDoNotMatchTheirSize) {
  test::TempDir dir;
  Image image = pattern(4, 4, 3);
  image.pixels.pop_back();
  EXPECT_THROW(write_png(dir.file("x.png"), image), ParamError);
  EXPECT_THROW(write_png(dir.file("x.png"), Image{}), ParamError);
}

}  // namespace
}  // namespace l2s::io
