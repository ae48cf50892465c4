// libFuzzer target: the Victoria Park text files. The first byte chooses the file the rest
// becomes (even: measurements.dat, odd: inputs.dat); the other is a small valid file, and the GPS
// file is a small valid MAT-file written at start-up. The loader must accept the data or throw
// std::runtime_error.
#include <matio.h>

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "datasets/victoria_park.h"
#include "fuzz/fuzz_input_file.h"

namespace {

constexpr char kMeasurements[] = "0.1 10 1.5 0.3\n0.2 12 1.6 0.2\n";
constexpr char kInputs[] = "0.05 1.0 0.0\n0.15 1.0 0.01\n0.25 1.0 0.0\n";

void WriteText(const std::filesystem::path& path, const std::string& text) {
  phdslam::fuzz::WriteInput(path, reinterpret_cast<const std::uint8_t*>(text.data()), text.size());
}

void WriteGps(const std::filesystem::path& path) {
  mat_t* mat = Mat_CreateVer(path.c_str(), nullptr, MAT_FT_MAT5);
  if (mat == nullptr) return;
  double time[2] = {0.0, 1000.0};
  double lo[2] = {0.0, 1.0};
  double la[2] = {0.0, 1.0};
  const std::pair<const char*, double*> vars[] = {{"timeGps", time}, {"Lo_m", lo}, {"La_m", la}};
  for (const auto& [name, values] : vars) {
    size_t dims[2] = {2, 1};
    matvar_t* var = Mat_VarCreate(name, MAT_C_DOUBLE, MAT_T_DOUBLE, 2, dims, values, 0);
    Mat_VarWrite(mat, var, MAT_COMPRESSION_NONE);
    Mat_VarFree(var);
  }
  Mat_Close(mat);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const auto root = phdslam::fuzz::ScratchFolder();
  const auto folder = root / "victoria-park";
  if (!std::filesystem::exists(folder / "aa3_gpsx.mat")) {
    std::filesystem::create_directories(folder);
    WriteGps(folder / "aa3_gpsx.mat");
  }
  const bool measurements = data[0] % 2 == 0;
  phdslam::fuzz::WriteInput(folder / (measurements ? "measurements.dat" : "inputs.dat"), data + 1,
                            size - 1);
  if (measurements) {
    WriteText(folder / "inputs.dat", kInputs);
  } else {
    WriteText(folder / "measurements.dat", kMeasurements);
  }
  try {
    (void)phdslam::datasets::LoadVictoriaParkData(root);
  } catch (const std::runtime_error&) {
  }
  return 0;
}
