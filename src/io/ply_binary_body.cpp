#include "ply_format.h"

#include <algorithm>
#include <cstring>

namespace iarap::io_detail {

namespace {

// Reads one binary scalar at p (bounds already checked) as a double; integers convert exactly.
double read_binary(const unsigned char* p, PlyType t, bool swap) {
  unsigned char b[8];
  const std::size_t n = type_size(t);
  for (std::size_t i = 0; i < n; ++i) b[i] = swap ? p[n - 1 - i] : p[i];
  switch (t) {
  case PlyType::int8: {
    std::int8_t v;
    std::memcpy(&v, b, 1);
    return v;
  }
  case PlyType::uint8:
    return b[0];
  case PlyType::int16: {
    std::int16_t v;
    std::memcpy(&v, b, 2);
    return v;
  }
  case PlyType::uint16: {
    std::uint16_t v;
    std::memcpy(&v, b, 2);
    return v;
  }
  case PlyType::int32: {
    std::int32_t v;
    std::memcpy(&v, b, 4);
    return v;
  }
  case PlyType::uint32: {
    std::uint32_t v;
    std::memcpy(&v, b, 4);
    return v;
  }
  case PlyType::float32: {
    float v;
    std::memcpy(&v, b, 4);
    return v;
  }
  case PlyType::float64: {
    double v;
    std::memcpy(&v, b, 8);
    return v;
  }
  }
  return 0.0;
}

bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

// The bytes of a binary body and the read position in them.
struct BinaryCursor {
  const unsigned char* bytes;
  std::size_t size, pos;
  bool swap;
};

// Reads record i of element e at the cursor: the coordinates into xyz (vertex), the index list of the
// role's list property into list; other properties are skipped. `fixed` is the record size of an element
// without lists (0 with lists).
void read_binary_record(const std::string& path, const PlyElement& e, std::int64_t i, std::size_t fixed,
                        BinaryCursor& c, double (&xyz)[3], std::vector<std::int64_t>& list) {
  const PlyRole& r = e.role;
  const auto need = [&](std::size_t n) {
    if (n > c.size - c.pos)
      fail_at_offset(path, static_cast<std::int64_t>(c.pos),
                     "file ends inside " + e.name + " record " + std::to_string(i) + " of " +
                         std::to_string(e.count));
  };
  if (fixed > 0) need(fixed);
  for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
    const PlyProperty& p = e.properties[pi];
    const int ppos = static_cast<int>(pi);
    if (!p.is_list) {
      const std::size_t n = type_size(p.type);
      need(n);
      if (ppos == r.x || ppos == r.y || ppos == r.z) {
        const double value = read_binary(c.bytes + c.pos, p.type, c.swap);
        xyz[ppos == r.x ? 0 : (ppos == r.y ? 1 : 2)] = value;
      }
      c.pos += n;
      continue;
    }
    const std::size_t cn = type_size(p.count_type);
    need(cn);
    const double count_value = read_binary(c.bytes + c.pos, p.count_type, c.swap);
    if (count_value < 0)
      fail_at_offset(path, static_cast<std::int64_t>(c.pos),
                     e.name + " " + std::to_string(i) + ": negative list length " +
                         std::to_string(static_cast<std::int64_t>(count_value)));
    c.pos += cn;
    const std::size_t n = static_cast<std::size_t>(count_value);
    const std::size_t item = type_size(p.type);
    if (n > (c.size - c.pos) / item) need(n * item);
    if (ppos == r.list) {
      list.resize(n);
      for (std::size_t k = 0; k < n; ++k)
        list[k] = static_cast<std::int64_t>(read_binary(c.bytes + c.pos + k * item, p.type, c.swap));
    }
    c.pos += n * item;
  }
}

} // namespace

void read_ply_binary_body(const std::string& path, const PlyHeader& header, const std::string& text,
                          std::size_t offset, PlyBody& body) {
  BinaryCursor c{reinterpret_cast<const unsigned char*>(text.data()), text.size(), offset,
                 (header.encoding == PlyEncoding::little_endian) != host_is_little_endian()};
  std::vector<std::int64_t> list;
  for (const PlyElement& e : header.elements) {
    const PlyRole& r = e.role;
    std::size_t fixed = 0; // record size when the element has no lists
    bool has_list = false;
    for (const PlyProperty& p : e.properties) {
      has_list = has_list || p.is_list;
      fixed += type_size(p.is_list ? p.count_type : p.type);
    }
    const std::size_t remaining = c.size - c.pos;
    // A count the remaining bytes cannot hold is rejected before anything is allocated for it.
    const std::size_t min_record = std::max<std::size_t>(fixed, 1);
    if (static_cast<std::uint64_t>(e.count) > remaining / min_record)
      fail_at_offset(path, static_cast<std::int64_t>(c.pos),
                     "header declares " + std::to_string(e.count) + " " + e.name + " records of at least " +
                         std::to_string(min_record) + " bytes but only " + std::to_string(remaining) +
                         " bytes follow");
    if (r.kind == PlyRole::vertex) body.positions.reserve(static_cast<std::size_t>(3 * e.count));
    if (r.kind == PlyRole::face) body.faces.reserve_triangles(static_cast<std::size_t>(e.count));
    double xyz[3] = {0, 0, 0};
    for (std::int64_t i = 0; i < e.count; ++i) {
      const std::size_t record_start = c.pos;
      read_binary_record(path, e, i, has_list ? 0 : fixed, c, xyz, list);
      store_ply_record(r, xyz, list, static_cast<std::int64_t>(record_start), body);
    }
    if (r.kind == PlyRole::vertex) body.num_vertices = e.count;
  }
  if (c.pos != c.size)
    fail_at_offset(path, static_cast<std::int64_t>(c.pos),
                   std::to_string(c.size - c.pos) + " bytes after the last element the header declares");
}

} // namespace iarap::io_detail
