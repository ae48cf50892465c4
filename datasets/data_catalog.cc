#include "datasets/data_catalog.h"

#include <stdexcept>

namespace phdslam::datasets {
namespace {

// The public PHD-SLAM 3.0 release (okaltiok/PHD-SLAM-3.0) at the last commit that holds ACFR's
// Victoria Park files, and the RFS-SLAM repository (kykleung/RFS-SLAM) with the tree detections.
constexpr const char* kPhdSlam3Release =
    "https://raw.githubusercontent.com/okaltiok/PHD-SLAM-3.0/"
    "e89c46933b51f085335fea001d30839d89ffffce/";
constexpr const char* kRfsSlamVictoriaPark =
    "https://raw.githubusercontent.com/kykleung/RFS-SLAM/"
    "aa5170be675391642c7ecfe6c7a3d39d218e674d/data/VictoriaPark/";

DataSetEntry Synthetic() {
  DataSetEntry e;
  e.name = "synthetic";
  e.title = "the PHD-SLAM 3.0 paper's synthetic scenario (Gao, Battistelli & Chisci)";
  e.folder = "phdslam3-synthetic";
  e.home =
      "https://github.com/okaltiok/PHD-SLAM-3.0 (folder 'Synthetic Data/measurements/SD data "
      "set/')";
  e.bundled = true;
  e.files = {{"phdslam3-synthetic/Environment_SLAM.mat", 214403,
              "55c29da7f6c109d7f650fc56b0918cac044186313cafcc17d7af5ec9ce86df0f",
              std::string(kPhdSlam3Release) +
                  "Synthetic%20Data/measurements/SD%20data%20set/Environment_SLAM.mat"}};
  return e;
}

DataSetEntry VictoriaPark() {
  const std::string acfr =
      std::string(kPhdSlam3Release) + "Victoria%20Park/measurements/VP%20data%20set/";
  DataSetEntry e;
  e.name = "victoria-park";
  e.title = "ACFR Victoria Park (Guivant & Nebot): tree detections, odometry, GPS";
  e.folder = "victoria-park";
  e.home =
      "https://github.com/kykleung/RFS-SLAM (data/VictoriaPark/) and "
      "https://github.com/okaltiok/PHD-SLAM-3.0 (history of 'Victoria Park/measurements/VP "
      "data set/'); ACFR: http://www-personal.acfr.usyd.edu.au/nebot/victoria_park.htm";
  e.files = {
      {"victoria-park/aa3_dr.mat", 1239216,
       "6ce2c4f757023b7d275cc14f24ff2ffcca21ea68cfa360bc854e620a706eb358", acfr + "aa3_dr.mat"},
      {"victoria-park/aa3_gpsx.mat", 89624,
       "521fc4c6e0ea3851ffb463c3d9c0578044e9178c4fb87f37c703bb587f38c755", acfr + "aa3_gpsx.mat"},
      {"victoria-park/acfr-info.txt", 1624,
       "f802e074e3697b2a2f22addd0b6b227fd4b21b12a11aa111425b2b0d807b50e2", acfr + "info.txt"},
      {"victoria-park/gps.dat", 147378,
       "944657cdaacdb9c421bf3a7ec1af95f05a8b9fefb513374f1f617bacc5426c07",
       std::string(kRfsSlamVictoriaPark) + "gps.dat"},
      {"victoria-park/inputs.dat", 2044185,
       "94353fa7a529f8a9e9770e69363d27472fe414f3637a107dce54a7f8db96e7d8",
       std::string(kRfsSlamVictoriaPark) + "inputs.dat"},
      {"victoria-park/measurements.dat", 2330856,
       "b0737e2d312cbb80d466a8f1d6048e11dd06939a5ffb63becc8b954cde149746",
       std::string(kRfsSlamVictoriaPark) + "measurements.dat"},
  };
  return e;
}

DataSetEntry Mrclam() {
  DataSetEntry e;
  e.name = "mrclam";
  e.title = "UTIAS MRCLAM dataset 6 (Leung, Halpern, Barfoot & Liu)";
  e.folder = "utias-mrclam";
  e.home = "http://asrl.utias.utoronto.ca/datasets/mrclam/ (section Downloads, MRCLAM_Dataset6)";
  e.archive_url = "http://asrl.utias.utoronto.ca/datasets/mrclam/MRCLAM_Dataset6.zip";
  e.files = {
      {"utias-mrclam/MRCLAM_Dataset6/Barcodes.dat", 404,
       "3448dfa8fdf7c6e52c4d778c9e3166a704fc1b3f388e5f274532ff1af3b37362", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Landmark_Groundtruth.dat", 1100,
       "eae8cb0aed1ad57910578ece4288d861940427cef95551fd53ca3997f16ecdb1", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot1_Groundtruth.dat", 2746910,
       "fee9661b3415b162e948c02cf56d3646ddc751c70f22c8cbd431fcde6d8a7b76", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot1_Measurement.dat", 77898,
       "571ca6c9978df9503062e014b0e46101623523d46a64dfe789e8aa1792b0e2e3", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot1_Odometry.dat", 2100915,
       "575febdf8022bd0a0da163e5078bb27413165196afe657974437aad215be5d0b", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot2_Groundtruth.dat", 3349445,
       "793fa0860e95a8b3d8422ae94614541649e895e89d7ab68c2d05e98965d1dc91", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot2_Measurement.dat", 161458,
       "36aaf4bde8f4880096f10324b490c0156e8ca71583375770a6fd0e725237fa04", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot2_Odometry.dat", 2210395,
       "dde2e7d70a8ff9355038d38e3e38a06419e060bff96607778506a01d90089701", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot3_Groundtruth.dat", 3197126,
       "1fffc5b2ff732a4bfd617ee35796f67ff6300eafcf3de0d645e3049df035fce8", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot3_Measurement.dat", 225298,
       "1975db530c0dfa3c215333cdc9432428bd6c3cb12348cd4aab12ed8a30f8dc1c", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot3_Odometry.dat", 2079597,
       "a4c50b28fd9fe8a4e4830ff53cbb7812a52fe2d88f2258c66e275232fb3c7326", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot4_Groundtruth.dat", 3443111,
       "eaba04bcb96f72f67aeb7e1098a994ac739e699cd03f0cfa21fd083a63a7f3d4", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot4_Measurement.dat", 96178,
       "b0d87a0d8c5bae9f761c42494a0d7f7d1ac48df4922a6af72811e2f2b82a063c", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot4_Odometry.dat", 1799369,
       "b5270104419bbb5b1e5ddf8d7bb31b6f4496a55f0d1b643b743af62ad06a31d6", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot5_Groundtruth.dat", 3217372,
       "fd98a23d555782ccad449d3cd4ff61e252891b6968248e68882b8cb6bfd4875c", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot5_Measurement.dat", 215338,
       "4f8bf6b4421a97b093503f6526365ae38f5d61361507c8bf1b0ad002a4c2e00e", ""},
      {"utias-mrclam/MRCLAM_Dataset6/Robot5_Odometry.dat", 2059503,
       "11297ae2f083f6d394f093b690ff4b467d3e466ab99525b9f02ee0fa4d15d817", ""},
  };
  return e;
}

}  // namespace

const std::vector<DataSetEntry>& DataSetCatalog() {
  static const std::vector<DataSetEntry> catalog = {Synthetic(), VictoriaPark(), Mrclam()};
  return catalog;
}

const DataSetEntry& FindDataSet(const std::string& name) {
  std::string known;
  for (const DataSetEntry& e : DataSetCatalog()) {
    if (e.name == name) return e;
    known += known.empty() ? e.name : ", " + e.name;
  }
  throw std::invalid_argument("unknown data set '" + name + "' (known: " + known + ")");
}

}  // namespace phdslam::datasets
