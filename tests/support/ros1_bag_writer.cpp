#include "support/ros1_bag_writer.hpp"

#include <bzlib.h>
#include <lz4frame.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <stdexcept>

namespace l2s::test {
namespace {

using Bytes = std::vector<std::uint8_t>;

template <typename T>
void put(Bytes& out, T value) {
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &value, sizeof(T));
}

void put_string(Bytes& out, const std::string& s) {
  put<std::uint32_t>(out, static_cast<std::uint32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

/// A `name=value` header field.
void field(Bytes& header, const std::string& name, const Bytes& value) {
  put<std::uint32_t>(header, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
  header.insert(header.end(), name.begin(), name.end());
  header.push_back('=');
  header.insert(header.end(), value.begin(), value.end());
}

template <typename T>
Bytes raw(T value) {
  Bytes b;
  put(b, value);
  return b;
}

Bytes text(const std::string& s) { return Bytes(s.begin(), s.end()); }

Bytes time_field(std::int64_t ns) {
  Bytes b;
  put<std::uint32_t>(b, static_cast<std::uint32_t>(ns / 1000000000));
  put<std::uint32_t>(b, static_cast<std::uint32_t>(ns % 1000000000));
  return b;
}

void record(Bytes& out, const Bytes& header, const Bytes& data) {
  put<std::uint32_t>(out, static_cast<std::uint32_t>(header.size()));
  out.insert(out.end(), header.begin(), header.end());
  put<std::uint32_t>(out, static_cast<std::uint32_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
}

Bytes compress(const std::string& compression, const Bytes& in) {
  if (compression == "bz2") {
    Bytes out(in.size() + in.size() / 100 + 600);
    auto size = static_cast<unsigned int>(out.size());
    if (BZ2_bzBuffToBuffCompress(reinterpret_cast<char*>(out.data()), &size,
                                 const_cast<char*>(reinterpret_cast<const char*>(in.data())),
                                 static_cast<unsigned int>(in.size()), 9, 0, 0) != BZ_OK)
      throw std::runtime_error("bz2 compression failed");
    out.resize(size);
    return out;
  }
  if (compression == "lz4") {
    Bytes out(LZ4F_compressFrameBound(in.size(), nullptr));
    const std::size_t size = LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), nullptr);
    if (LZ4F_isError(size)) throw std::runtime_error("lz4 compression failed");
    out.resize(size);
    return out;
  }
  return in;
}

struct Connection {
  std::uint32_t id;
  std::string topic, type;
};

Bytes connection_record(const Connection& c) {
  Bytes header, data;
  field(header, "op", raw<std::uint8_t>(0x07));
  field(header, "conn", raw<std::uint32_t>(c.id));
  field(header, "topic", text(c.topic));
  field(data, "topic", text(c.topic));
  field(data, "type", text(c.type));
  field(data, "md5sum", text("*"));
  field(data, "message_definition", text("# written by l2scalib's tests"));
  Bytes out;
  record(out, header, data);
  return out;
}

}  // namespace

void write_ros1_bag(const std::string& path, const std::vector<BagMessageToWrite>& messages,
                    const std::string& compression, int messages_per_chunk) {
  std::map<std::string, Connection> connections;
  for (const auto& m : messages)
    if (!connections.count(m.topic))
      connections[m.topic] = {static_cast<std::uint32_t>(connections.size()), m.topic, m.type};

  Bytes file(std::begin("#ROSBAG V2.0\n"), std::end("#ROSBAG V2.0\n") - 1);
  const std::size_t bag_header_at = file.size();
  const auto bag_header = [&](std::uint64_t index_pos, std::uint32_t chunks) {
    Bytes header, padded;
    field(header, "op", raw<std::uint8_t>(0x03));
    field(header, "index_pos", raw<std::uint64_t>(index_pos));
    field(header, "conn_count", raw<std::uint32_t>(static_cast<std::uint32_t>(connections.size())));
    field(header, "chunk_count", raw<std::uint32_t>(chunks));
    // The header record fills 4096 bytes, so that a recorder can rewrite it in place.
    padded.assign(4096 - 8 - header.size(), ' ');
    Bytes out;
    record(out, header, padded);
    return out;
  };
  const Bytes placeholder = bag_header(0, 0);
  file.insert(file.end(), placeholder.begin(), placeholder.end());

  Bytes chunk_infos;
  std::uint32_t chunk_count = 0;
  std::map<std::uint32_t, bool> written;  // connections already in an earlier chunk
  for (std::size_t first = 0; first < messages.size(); first += static_cast<std::size_t>(messages_per_chunk)) {
    const std::size_t last = std::min(messages.size(), first + static_cast<std::size_t>(messages_per_chunk));
    Bytes inner;
    std::map<std::uint32_t, std::vector<std::pair<std::int64_t, std::uint32_t>>> index;
    std::int64_t start = messages[first].time_ns, end = start;
    for (std::size_t k = first; k < last; ++k) {
      const Connection& c = connections.at(messages[k].topic);
      if (!written[c.id]) {
        const Bytes rec = connection_record(c);
        inner.insert(inner.end(), rec.begin(), rec.end());
        written[c.id] = true;
      }
      index[c.id].emplace_back(messages[k].time_ns, static_cast<std::uint32_t>(inner.size()));
      Bytes header;
      field(header, "op", raw<std::uint8_t>(0x02));
      field(header, "conn", raw<std::uint32_t>(c.id));
      field(header, "time", time_field(messages[k].time_ns));
      record(inner, header, messages[k].data);
      start = std::min(start, messages[k].time_ns);
      end = std::max(end, messages[k].time_ns);
    }
    const std::uint64_t chunk_at = file.size();
    Bytes header;
    field(header, "op", raw<std::uint8_t>(0x05));
    field(header, "compression", text(compression));
    field(header, "size", raw<std::uint32_t>(static_cast<std::uint32_t>(inner.size())));
    record(file, header, compress(compression, inner));
    for (const auto& [id, entries] : index) {
      Bytes index_header, data;
      field(index_header, "op", raw<std::uint8_t>(0x04));
      field(index_header, "ver", raw<std::uint32_t>(1));
      field(index_header, "conn", raw<std::uint32_t>(id));
      field(index_header, "count", raw<std::uint32_t>(static_cast<std::uint32_t>(entries.size())));
      for (const auto& [t, offset] : entries) {
        const Bytes tf = time_field(t);
        data.insert(data.end(), tf.begin(), tf.end());
        put<std::uint32_t>(data, offset);
      }
      record(file, index_header, data);
    }
    Bytes info_header, info_data;
    field(info_header, "op", raw<std::uint8_t>(0x06));
    field(info_header, "ver", raw<std::uint32_t>(1));
    field(info_header, "chunk_pos", raw<std::uint64_t>(chunk_at));
    field(info_header, "start_time", time_field(start));
    field(info_header, "end_time", time_field(end));
    field(info_header, "count", raw<std::uint32_t>(static_cast<std::uint32_t>(index.size())));
    for (const auto& [id, entries] : index) {
      put<std::uint32_t>(info_data, id);
      put<std::uint32_t>(info_data, static_cast<std::uint32_t>(entries.size()));
    }
    record(chunk_infos, info_header, info_data);
    ++chunk_count;
  }
  const std::uint64_t index_pos = file.size();
  for (const auto& [topic, c] : connections) {
    const Bytes rec = connection_record(c);
    file.insert(file.end(), rec.begin(), rec.end());
  }
  file.insert(file.end(), chunk_infos.begin(), chunk_infos.end());
  const Bytes final_header = bag_header(index_pos, chunk_count);
  std::copy(final_header.begin(), final_header.end(), file.begin() + static_cast<std::ptrdiff_t>(bag_header_at));
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(file.data()), static_cast<std::streamsize>(file.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

std::vector<std::uint8_t> point_cloud2_message(const LidarCloud& cloud, const std::vector<CloudField>& layout,
                                               std::int64_t stamp_ns, const std::string& frame_id,
                                               std::uint32_t height, bool big_endian, std::uint32_t point_step,
                                               const std::vector<double>& point_times) {
  static const std::map<std::uint8_t, std::uint32_t> sizes = {{1, 1}, {2, 1}, {3, 2}, {4, 2},
                                                              {5, 4}, {6, 4}, {7, 4}, {8, 8}};
  std::vector<std::uint32_t> offsets;
  std::uint32_t packed = 0;
  for (const auto& f : layout) {
    offsets.push_back(packed);
    packed += sizes.at(f.datatype);
  }
  const std::uint32_t step = std::max(point_step, packed);
  const auto width = static_cast<std::uint32_t>(cloud.size() / height);
  Bytes out;
  put<std::uint32_t>(out, 7);  // seq
  const Bytes stamp = time_field(stamp_ns);
  out.insert(out.end(), stamp.begin(), stamp.end());
  put_string(out, frame_id);
  put<std::uint32_t>(out, height);
  put<std::uint32_t>(out, width);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(layout.size()));
  for (std::size_t k = 0; k < layout.size(); ++k) {
    put_string(out, layout[k].name);
    put<std::uint32_t>(out, offsets[k]);
    put<std::uint8_t>(out, layout[k].datatype);
    put<std::uint32_t>(out, 1);
  }
  put<std::uint8_t>(out, big_endian ? 1 : 0);
  put<std::uint32_t>(out, step);
  put<std::uint32_t>(out, step * width);
  Bytes data(static_cast<std::size_t>(step) * width * height, 0xEE);  // padding bytes are junk
  for (std::size_t i = 0; i < static_cast<std::size_t>(width) * height; ++i) {
    for (std::size_t k = 0; k < layout.size(); ++k) {
      const std::string& name = layout[k].name;
      double v = 0.0;
      if (name == "x" || name == "y" || name == "z") v = cloud.points[i][name[0] - 'x'];
      else if ((name == "intensity" || name == "i") && cloud.has_intensity()) v = cloud.intensity[i];
      else if ((name == "ring" || name == "laser_id") && cloud.has_ring()) v = cloud.ring[i];
      else if ((name == "time" || name == "t" || name == "timestamp") && !point_times.empty()) v = point_times[i];
      std::uint8_t bytes[8];
      switch (layout[k].datatype) {
        case 1: { auto x = static_cast<std::int8_t>(v); std::memcpy(bytes, &x, 1); break; }
        case 2: { auto x = static_cast<std::uint8_t>(v); std::memcpy(bytes, &x, 1); break; }
        case 3: { auto x = static_cast<std::int16_t>(v); std::memcpy(bytes, &x, 2); break; }
        case 4: { auto x = static_cast<std::uint16_t>(v); std::memcpy(bytes, &x, 2); break; }
        case 5: { auto x = static_cast<std::int32_t>(v); std::memcpy(bytes, &x, 4); break; }
        case 6: { auto x = static_cast<std::uint32_t>(v); std::memcpy(bytes, &x, 4); break; }
        case 7: { auto x = static_cast<float>(v); std::memcpy(bytes, &x, 4); break; }
        default: std::memcpy(bytes, &v, 8);
      }
      const std::uint32_t size = sizes.at(layout[k].datatype);
      if (big_endian) std::reverse(bytes, bytes + size);
      std::memcpy(data.data() + i * step + offsets[k], bytes, size);
    }
  }
  put<std::uint32_t>(out, static_cast<std::uint32_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
  put<std::uint8_t>(out, 0);  // is_dense: organised clouds keep NaN
  return out;
}

namespace {

void put_header(Bytes& out, std::int64_t stamp_ns, const std::string& frame_id) {
  put<std::uint32_t>(out, 1);  // seq
  const Bytes stamp = time_field(stamp_ns);
  out.insert(out.end(), stamp.begin(), stamp.end());
  put_string(out, frame_id);
}

}  // namespace

std::vector<std::uint8_t> image_message(std::int64_t stamp_ns, const std::string& frame_id, int width, int height,
                                        const std::string& encoding, std::uint32_t step,
                                        const std::vector<std::uint8_t>& pixels, bool big_endian) {
  Bytes out;
  put_header(out, stamp_ns, frame_id);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(height));
  put<std::uint32_t>(out, static_cast<std::uint32_t>(width));
  put_string(out, encoding);
  put<std::uint8_t>(out, big_endian ? 1 : 0);
  put<std::uint32_t>(out, step);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(pixels.size()));
  out.insert(out.end(), pixels.begin(), pixels.end());
  return out;
}

std::vector<std::uint8_t> compressed_image_message(std::int64_t stamp_ns, const std::string& frame_id,
                                                   const std::string& format, const std::vector<std::uint8_t>& bytes) {
  Bytes out;
  put_header(out, stamp_ns, frame_id);
  put_string(out, format);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(bytes.size()));
  out.insert(out.end(), bytes.begin(), bytes.end());
  return out;
}

std::vector<std::uint8_t> camera_info_message(std::int64_t stamp_ns, const std::string& frame_id,
                                              const CameraInfo& camera) {
  Bytes out;
  put_header(out, stamp_ns, frame_id);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(camera.height));
  put<std::uint32_t>(out, static_cast<std::uint32_t>(camera.width));
  put_string(out, camera.distortion_model);
  put<std::uint32_t>(out, static_cast<std::uint32_t>(camera.distortion_coefficients.size()));
  for (double d : camera.distortion_coefficients) put<double>(out, d);
  for (int k = 0; k < 9; ++k) put<double>(out, camera.camera_matrix(k / 3, k % 3));
  for (int k = 0; k < 9; ++k) put<double>(out, camera.rectification_matrix(k / 3, k % 3));
  for (int k = 0; k < 12; ++k) put<double>(out, camera.projection_matrix(k / 4, k % 4));
  put<std::uint32_t>(out, 0);  // binning_x
  put<std::uint32_t>(out, 0);  // binning_y
  for (int k = 0; k < 4; ++k) put<std::uint32_t>(out, 0);  // roi x_offset, y_offset, height, width
  put<std::uint8_t>(out, 0);   // roi do_rectify
  return out;
}

}  // namespace l2s::test
