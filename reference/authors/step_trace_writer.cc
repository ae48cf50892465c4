#include "reference/authors/step_trace_writer.h"

#include <array>
#include <charconv>
#include <filesystem>
#include <stdexcept>

namespace phdslam::authors {
namespace {

std::ofstream OpenCsv(const std::filesystem::path& path, const char* header) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write the trace file");
  out << header << '\n';
  return out;
}

/// The shortest text that reads back as exactly `v` (the comparison needs every bit).
std::string Num(double v) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), v);
  return {buf.data(), result.ptr};
}

void WriteComponents(std::ofstream& out, int step, int idx, int list,
                     const std::vector<phd::GaussianComponent>& components) {
  for (std::size_t c = 0; c < components.size(); ++c) {
    const phd::GaussianComponent& g = components[c];
    out << step << ',' << idx << ',' << list << ',' << c << ',' << Num(g.log_weight) << ','
        << Num(g.mean[0]) << ',' << Num(g.mean[1]) << ',' << Num(g.cov(0, 0)) << ','
        << Num(g.cov(0, 1)) << ',' << Num(g.cov(1, 1)) << '\n';
  }
}

void WriteSymmetric3(std::ofstream& out, const Mat3& m) {
  out << Num(m(0, 0)) << ',' << Num(m(0, 1)) << ',' << Num(m(0, 2)) << ',' << Num(m(1, 1)) << ','
      << Num(m(1, 2)) << ',' << Num(m(2, 2));
}

}  // namespace

StepTraceWriter::StepTraceWriter(const std::string& folder, int map_every, int last_step)
    : map_every_(map_every), last_step_(last_step) {
  const std::filesystem::path dir(folder);
  std::filesystem::create_directories(dir);
  particles_ = OpenCsv(dir / "particles.csv",
                       "step,particle,prior_x,prior_y,prior_theta,prior_pxx,prior_pxy,prior_pxt,"
                       "prior_pyy,prior_pyt,prior_ptt,components,x,y,theta,log_weight_sampled");
  proposals_ = OpenCsv(dir / "proposals.csv",
                       "step,particle,component,log_weight,x,y,theta,pxx,pxy,pxt,pyy,pyt,ptt");
  states_ = OpenCsv(dir / "states.csv", "step,particle,log_weight,active,passive,births");
  maps_ = OpenCsv(dir / "maps.csv", "step,particle,list,component,log_weight,x,y,pxx,pxy,pyy");
  estimate_ = OpenCsv(dir / "estimate.csv", "step,x,y,theta,map_size,ess,resampled,sources");
}

void StepTraceWriter::Sampled(int step, int idx, const Pose& mu0, const Mat3& sigma0,
                              const filters::PreparedProposal& proposal,
                              const filters::PhdParticle& p) {
  const std::size_t components = proposal.mixture.size();
  particles_ << step << ',' << idx << ',' << Num(mu0[0]) << ',' << Num(mu0[1]) << ',' << Num(mu0[2])
             << ',';
  WriteSymmetric3(particles_, sigma0);
  particles_ << ',' << components << ',' << Num(p.pose[0]) << ',' << Num(p.pose[1]) << ','
             << Num(p.pose[2]) << ',' << Num(p.log_weight) << '\n';
  for (std::size_t j = 0; j < components; ++j) {
    const Pose& m = proposal.mixture.means[j];
    proposals_ << step << ',' << idx << ',' << j << ',' << Num(proposal.mixture.log_weights[j])
               << ',' << Num(m[0]) << ',' << Num(m[1]) << ',' << Num(m[2]) << ',';
    WriteSymmetric3(proposals_, proposal.mixture.covs[j]);
    proposals_ << '\n';
  }
}

void StepTraceWriter::Updated(int step, int idx, const filters::PhdParticle& p) {
  const std::vector<phd::GaussianComponent> passive = p.map.gm.passive();
  states_ << step << ',' << idx << ',' << Num(p.log_weight) << ',' << p.map.gm.active().size()
          << ',' << passive.size() << ',' << p.map.births.size() << '\n';
  if (map_every_ > 0 && (step % map_every_ == 0 || step == last_step_)) {
    WriteComponents(maps_, step, idx, 0, p.map.gm.active());
    WriteComponents(maps_, step, idx, 1, passive);
  }
}

void StepTraceWriter::Resampled(int /*step*/, const std::vector<int>& sources) {
  sources_ = sources;
}

void StepTraceWriter::Estimated(int step, const filters::StepOutput& out, int map_size) {
  estimate_ << step << ',' << Num(out.pose[0]) << ',' << Num(out.pose[1]) << ',' << Num(out.pose[2])
            << ',' << map_size << ',' << Num(out.diag.ess) << ',' << (out.diag.resampled ? 1 : 0)
            << ',';
  for (std::size_t i = 0; i < sources_.size(); ++i) estimate_ << (i ? " " : "") << sources_[i];
  estimate_ << '\n';
  sources_.clear();
}

}  // namespace phdslam::authors
