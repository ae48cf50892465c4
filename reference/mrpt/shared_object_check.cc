#include "reference/mrpt/shared_object_check.h"

#include <elf.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace phdslam::reference {
namespace {

namespace fs = std::filesystem;

#if defined(__x86_64__)
constexpr std::uint16_t kMachine = EM_X86_64;
#elif defined(__aarch64__)
constexpr std::uint16_t kMachine = EM_AARCH64;
#else
constexpr std::uint16_t kMachine = EM_NONE;  // not checked
#endif

[[noreturn]] void RefusePlugin(const fs::path& path, const std::string& why) {
  throw std::runtime_error("the MRPT baselines' plugin " + path.string() + " " + why +
                           ": rebuild or reinstall phdslam (or correct PHDSLAM_MRPT_PLUGIN)");
}

std::uintmax_t PluginFileSize(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) RefusePlugin(path, "does not exist");
  if (!fs::is_regular_file(path, ec)) RefusePlugin(path, "is not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) RefusePlugin(path, "cannot be read (" + ec.message() + ")");
  return size;
}

// True when [offset, offset + length) lies inside a file of `size` bytes.
bool InsideFile(std::uint64_t offset, std::uint64_t length, std::uintmax_t size) {
  return offset <= size && length <= size - offset;
}

void RequireElfHeader(const fs::path& path, const Elf64_Ehdr& header) {
  if (std::memcmp(header.e_ident, ELFMAG, SELFMAG) != 0) RefusePlugin(path, "is not an ELF file");
  if (header.e_ident[EI_CLASS] != ELFCLASS64 || header.e_ident[EI_DATA] != ELFDATA2LSB) {
    RefusePlugin(path, "is an ELF file of another class or byte order");
  }
  if (header.e_type != ET_DYN) RefusePlugin(path, "is not a shared object");
  if (kMachine != EM_NONE && header.e_machine != kMachine) {
    RefusePlugin(path, "is built for another architecture");
  }
  if (header.e_phentsize != sizeof(Elf64_Phdr) ||
      (header.e_shnum != 0 && header.e_shentsize != sizeof(Elf64_Shdr))) {
    RefusePlugin(path, "has malformed ELF headers");
  }
}

void RequireSegmentsInside(const fs::path& path, std::ifstream& in, const Elf64_Ehdr& header,
                           std::uintmax_t size) {
  std::vector<Elf64_Phdr> segments(header.e_phnum);
  in.seekg(static_cast<std::streamoff>(header.e_phoff));
  in.read(reinterpret_cast<char*>(segments.data()),
          static_cast<std::streamsize>(segments.size() * sizeof(Elf64_Phdr)));
  if (!in) RefusePlugin(path, "is cut short (its program headers cannot be read)");
  for (const Elf64_Phdr& segment : segments) {
    if (segment.p_type == PT_LOAD && !InsideFile(segment.p_offset, segment.p_filesz, size)) {
      RefusePlugin(path, "is cut short (" + std::to_string(size) +
                             " bytes; a loaded segment ends at " +
                             std::to_string(segment.p_offset + segment.p_filesz) + ")");
    }
  }
}

}  // namespace

void RequireCompleteSharedObject(const fs::path& path) {
  const std::uintmax_t size = PluginFileSize(path);
  Elf64_Ehdr header{};
  if (size < sizeof(header)) {
    RefusePlugin(path,
                 "is cut short (" + std::to_string(size) + " bytes, less than an ELF header)");
  }
  std::ifstream in(path, std::ios::binary);
  in.read(reinterpret_cast<char*>(&header), sizeof(header));
  if (!in) RefusePlugin(path, "cannot be read");
  RequireElfHeader(path, header);
  if (!InsideFile(header.e_phoff, std::uint64_t{header.e_phnum} * sizeof(Elf64_Phdr), size)) {
    RefusePlugin(path, "is cut short (its program headers lie past its end)");
  }
  if (!InsideFile(header.e_shoff, std::uint64_t{header.e_shnum} * header.e_shentsize, size)) {
    RefusePlugin(path, "is cut short (" + std::to_string(size) +
                           " bytes; its section headers lie past its end)");
  }
  RequireSegmentsInside(path, in, header, size);
}

}  // namespace phdslam::reference
