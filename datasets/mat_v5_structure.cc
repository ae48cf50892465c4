#include "datasets/mat_v5_structure.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "datasets/text_fields.h"

namespace phdslam::datasets {
namespace {

constexpr std::size_t kV5HeaderBytes = 128;
constexpr std::size_t kTagBytes = 8;

enum DataType : std::uint32_t {
  kMiInt8 = 1,
  kMiUint8 = 2,
  kMiInt16 = 3,
  kMiUint16 = 4,
  kMiInt32 = 5,
  kMiUint32 = 6,
  kMiSingle = 7,
  kMiDouble = 9,
  kMiInt64 = 12,
  kMiUint64 = 13,
  kMiMatrix = 14,
  kMiCompressed = 15,
  kMiUtf8 = 16,
  kMiUtf16 = 17,
  kMiUtf32 = 18,
};

constexpr std::uint32_t kCharClass = 4;
constexpr std::uint32_t kFirstNumericClass = 6;  // double
constexpr std::uint32_t kLastNumericClass = 15;  // uint64
constexpr std::uint32_t kComplexFlag = 0x0800;

/// Bytes per element of a stored data type; 0 for a type that cannot hold array data.
std::uint64_t ElementBytes(std::uint32_t type) {
  switch (type) {
    case kMiInt8:
    case kMiUint8:
    case kMiUtf8:
      return 1;
    case kMiInt16:
    case kMiUint16:
    case kMiUtf16:
      return 2;
    case kMiInt32:
    case kMiUint32:
    case kMiSingle:
    case kMiUtf32:
      return 4;
    case kMiDouble:
    case kMiInt64:
    case kMiUint64:
      return 8;
    default:
      return 0;
  }
}

/// A byte buffer read in the file's byte order.
struct Buffer {
  std::string_view bytes;
  bool swap = false;

  [[nodiscard]] std::uint32_t U32(std::size_t offset) const {
    std::uint32_t v = 0;
    std::memcpy(&v, bytes.data() + offset, sizeof(v));
    return swap ? __builtin_bswap32(v) : v;
  }
};

/// One data element: its type, byte count, where its data starts and where the next one starts.
struct Element {
  std::uint32_t type = 0;
  std::uint64_t size = 0;
  std::size_t data = 0;
  std::size_t next = 0;
};

[[noreturn]] void FailMatV5(const std::string& where, const std::string& what) {
  throw std::runtime_error(where + ": " + what);
}

/// The element whose tag starts at `offset`; it must end by `end`. `padded` elements are followed
/// by padding to a multiple of 8 bytes (all but compressed ones).
Element ReadElement(const Buffer& buf, std::size_t offset, std::size_t end, bool padded,
                    const std::string& where) {
  if (end - offset < kTagBytes) {
    FailMatV5(where, "ends inside a data element tag at byte " + std::to_string(offset) + " (" +
                         std::to_string(end - offset) + " of 8 bytes)");
  }
  Element e;
  const std::uint32_t first = buf.U32(offset);
  if ((first >> 16) != 0) {  // small data element: type and size share the first word
    e.type = first & 0xffffU;
    e.size = first >> 16;
    if (e.size > 4) {
      FailMatV5(where, "small data element at byte " + std::to_string(offset) + " claims " +
                           std::to_string(e.size) + " bytes (at most 4)");
    }
    e.data = offset + 4;
    e.next = offset + kTagBytes;
    return e;
  }
  e.type = first;
  e.size = buf.U32(offset + 4);
  e.data = offset + kTagBytes;
  if (e.size > end - e.data) {
    FailMatV5(where, "data element at byte " + std::to_string(offset) + " declares " +
                         std::to_string(e.size) + " bytes but only " +
                         std::to_string(end - e.data) +
                         " remain (the file is truncated or corrupt)");
  }
  const std::uint64_t padding = padded ? (kTagBytes - e.size % kTagBytes) % kTagBytes : 0;
  e.next = e.data + static_cast<std::size_t>(e.size);
  e.next += static_cast<std::size_t>(std::min<std::uint64_t>(padding, end - e.next));
  return e;
}

/// Checks that an array part (real or imaginary) stores exactly `count` elements.
void CheckArrayPart(const Buffer& buf, std::size_t& p, std::size_t end, std::uint64_t count,
                    const char* part, const std::string& where) {
  const Element e = ReadElement(buf, p, end, true, where);
  const std::uint64_t each = ElementBytes(e.type);
  if (each == 0) {
    FailMatV5(where,
              std::string(part) + " part has unsupported data type " + std::to_string(e.type));
  }
  const bool overflows = count != 0 && each > std::numeric_limits<std::uint64_t>::max() / count;
  if (overflows || e.size != count * each) {
    FailMatV5(where, "its dimensions declare " + std::to_string(count) + " elements but its " +
                         part + " part stores " + std::to_string(e.size / each) + " (" +
                         std::to_string(e.size) + " bytes of " + std::to_string(each) + ")");
  }
  p = e.next;
}

/// Product of the dimensions in a dimensions element; throws on a negative or overflowing value.
std::uint64_t ElementCount(const Buffer& buf, const Element& dims, const std::string& where) {
  if (dims.type != kMiInt32 || dims.size < 8 || dims.size % 4 != 0) {
    FailMatV5(where, "malformed dimensions element");
  }
  std::uint64_t count = 1;
  for (std::size_t i = 0; i < dims.size / 4; ++i) {
    const auto d = static_cast<std::int32_t>(buf.U32(dims.data + 4 * i));
    if (d < 0) FailMatV5(where, "negative dimension " + std::to_string(d));
    const auto ud = static_cast<std::uint64_t>(d);
    if (ud != 0 && count > std::numeric_limits<std::uint64_t>::max() / ud) {
      FailMatV5(where, "dimensions overflow");
    }
    count *= ud;
  }
  return count;
}

/// Checks the sub-elements of an miMATRIX element `m`.
void CheckMatrix(const Buffer& buf, const Element& m, const std::string& where) {
  const std::size_t end = m.data + static_cast<std::size_t>(m.size);
  std::size_t p = m.data;
  const Element flags = ReadElement(buf, p, end, true, where);
  if (flags.type != kMiUint32 || flags.size < 4) FailMatV5(where, "malformed array flags element");
  const std::uint32_t flag_word = buf.U32(flags.data);
  const std::uint32_t array_class = flag_word & 0xffU;
  const bool numeric = array_class >= kFirstNumericClass && array_class <= kLastNumericClass;
  if (!numeric && array_class != kCharClass) return;  // cell, struct, sparse, ...: libmatio's care
  p = flags.next;
  const Element dims = ReadElement(buf, p, end, true, where);
  const std::uint64_t count = ElementCount(buf, dims, where);
  p = dims.next;
  const Element name = ReadElement(buf, p, end, true, where);
  const std::string named =
      where + " ('" +
      text::Printable(buf.bytes.substr(name.data, static_cast<std::size_t>(name.size)), 63) + "')";
  p = name.next;
  CheckArrayPart(buf, p, end, count, "real", named);
  if ((flag_word & kComplexFlag) != 0) CheckArrayPart(buf, p, end, count, "imaginary", named);
}

/// Deflate expands at most 1032:1 (a 258-byte match per 2 bits), so a compressed element of n
/// bytes cannot inflate to more than 1032 n: a larger declared size is refused without inflating.
constexpr std::uint64_t kMaxDeflateRatio = 1032;

/// First step of the output buffer's growth while inflating.
constexpr std::size_t kInflateChunkBytes = std::size_t{1} << 16;

/// Inflates from `zs` until `out` holds `want` bytes, growing `out` with what actually arrives
/// (at most doubling it per step), so that a declared size the stream does not reach never gets
/// allocated. Throws when the stream ends first.
void InflateTo(z_stream& zs, std::string& out, std::size_t want, const std::string& where) {
  while (out.size() < want) {
    const std::size_t from = out.size();
    const std::size_t step = std::min(want - from, std::max(from, kInflateChunkBytes));
    out.resize(from + step);
    zs.next_out = reinterpret_cast<Bytef*>(out.data() + from);
    zs.avail_out = static_cast<uInt>(step);
    int rc = Z_OK;
    while (zs.avail_out > 0 && rc == Z_OK) rc = inflate(&zs, Z_NO_FLUSH);
    if (zs.avail_out > 0) {
      const std::size_t produced = out.size() - zs.avail_out;
      FailMatV5(where,
                "its compressed data inflates to only " + std::to_string(produced) + " of " +
                    std::to_string(want) + " declared bytes" +
                    (zs.msg != nullptr ? std::string(" (zlib: ") + zs.msg + ")" : std::string()) +
                    "; the file is truncated or corrupt");
    }
  }
}

/// Inflates a compressed variable completely: the inner tag's declared size must be produced.
std::string Inflate(std::string_view compressed, bool swap, const std::string& where) {
  z_stream zs{};
  if (inflateInit(&zs) != Z_OK) FailMatV5(where, "cannot start decompression");
  struct Ender {
    z_stream* zs;
    ~Ender() { inflateEnd(zs); }
  } ender{&zs};
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data()));
  zs.avail_in = static_cast<uInt>(compressed.size());
  std::string out;
  InflateTo(zs, out, kTagBytes, where);
  const Buffer head{out, swap};
  const std::uint32_t first = head.U32(0);
  if (first != kMiMatrix) FailMatV5(where, "compressed data does not hold an array");
  const std::uint64_t declared = head.U32(4);
  if (declared > kMaxMatVariableBytes - kTagBytes) {
    FailMatV5(where, "declares " + std::to_string(declared) + " bytes, more than the " +
                         std::to_string(kMaxMatVariableBytes) + " accepted for one variable");
  }
  if (declared + kTagBytes > kMaxDeflateRatio * compressed.size()) {
    FailMatV5(where, "declares " + std::to_string(declared) + " bytes, but its " +
                         std::to_string(compressed.size()) +
                         " compressed bytes cannot inflate to more than " +
                         std::to_string(kMaxDeflateRatio * compressed.size()) +
                         " (deflate expands at most 1032:1); the file is truncated or corrupt");
  }
  InflateTo(zs, out, kTagBytes + static_cast<std::size_t>(declared), where);
  return out;
}

/// True when `bytes` starts with a 128-byte MAT-file header of the given version number (0x0100
/// for version 5, 0x0200 for 7.3), stored in the byte order its endian indicator gives.
bool HasHeaderVersion(std::string_view bytes, unsigned version) {
  if (bytes.size() < kV5HeaderBytes) return false;
  const std::string_view endian = bytes.substr(126, 2);
  const auto v0 = static_cast<unsigned char>(bytes[124]);
  const auto v1 = static_cast<unsigned char>(bytes[125]);
  if (endian == "IM") return v0 == (version & 0xffU) && v1 == (version >> 8);
  if (endian == "MI") return v0 == (version >> 8) && v1 == (version & 0xffU);
  return false;
}

}  // namespace

bool IsMatV5(std::string_view bytes) { return HasHeaderVersion(bytes, 0x0100); }

bool IsMatV73(std::string_view bytes) { return HasHeaderVersion(bytes, 0x0200); }

void CheckMatV5Structure(std::string_view bytes, const std::string& where) {
  if (!IsMatV5(bytes)) FailMatV5(where, "not a version 5 MAT-file");
  const Buffer file{bytes, bytes.substr(126, 2) == "MI"};
  std::size_t offset = kV5HeaderBytes;
  for (int index = 1; offset < bytes.size(); ++index) {
    const std::string variable = where + ", variable #" + std::to_string(index);
    const Element e = ReadElement(file, offset, bytes.size(), true, variable);
    if (e.type == kMiCompressed) {
      const std::string inflated =
          Inflate(bytes.substr(e.data, static_cast<std::size_t>(e.size)), file.swap, variable);
      const Buffer inner{inflated, file.swap};
      CheckMatrix(inner, ReadElement(inner, 0, inflated.size(), true, variable), variable);
      offset = e.data + static_cast<std::size_t>(e.size);
    } else {
      if (e.type == kMiMatrix) CheckMatrix(file, e, variable);
      offset = e.next;
    }
  }
}

}  // namespace phdslam::datasets
