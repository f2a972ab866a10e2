#include "sedwave/forward/experiment/linear_run_file.hpp"

#include "sedwave/io/hdf5.hpp"
#include "run_file_parts.hpp"

namespace sedwave::forward::experiment {

using namespace linear;  // the file holds the linear engine's results

void write_linear_run_file(const std::filesystem::path& path, const ChannelScene& scene,
                           const std::vector<channel::PreparationReport>& preparations, const EnsembleResult& e) {
  io::write_file_atomically(path, [&](hid_t file) {
    write_run_header(file, scene.text);
    io::write_string_attribute(file, "engine", "linear");
    for (std::size_t k = 0; k < e.members.size(); ++k) {
      const LinearResult& r = e.members[k];
      io::Handle member = io::create_group(file, "member_" + std::to_string(k));
      io::write_attribute(member, "seed", static_cast<std::int64_t>(scene.geometry.seed + k));
      if (k < preparations.size()) {
        io::Handle packing = io::create_group(member, "packing");
        write_stats(packing, preparations[k]);
      }
      io::write(member, "layer_z", r.layer_z.data(), r.layer_z.size());
      io::write_string_attribute(member, "layer_z_unit", "d, from the driven wall's mean surface");
      io::write(member, "layer_grains", r.layer_grains.data(), r.layer_grains.size());
      std::vector<double> re, im;
      for (const auto& u : r.layer_field) {
        re.push_back(u.real());
        im.push_back(u.imag());
      }
      io::write(member, "layer_field_real", re.data(), re.size());
      io::write(member, "layer_field_imag", im.data(), im.size());
      io::write_string_attribute(member, "layer_field_unit",
                                 "wall amplitude A; mean displacement along the drive axis is Re(U exp(i omega t))");
      write_fit(member, r.fit);
      number(member, "two_wave_alpha_hat", r.waves.alpha, "Np per d");
      number(member, "two_wave_k_hat", r.waves.k, "rad per d");
      number(member, "reflection", r.waves.reflection, "1 (at the absorbing layer's start; indicative only: in a disordered channel with alpha L >> 1 scattering noise dominates it)");
      io::write_attribute(member, "contacts", r.state_changes.contacts);
      io::write_attribute(member, "contacts_opening", r.state_changes.opening);
      io::write_attribute(member, "contacts_sliding", r.state_changes.sliding);
      io::write_attribute(member, "gaps", r.state_changes.gaps);
      io::write_attribute(member, "gaps_closing", r.state_changes.closing);
      std::vector<double> ladder_a;
      std::vector<std::int64_t> ladder_open, ladder_slide, ladder_close;
      for (const StateChanges& c : r.amplitude_ladder) {
        ladder_a.push_back(c.amplitude);
        ladder_open.push_back(c.opening);
        ladder_slide.push_back(c.sliding);
        ladder_close.push_back(c.closing);
      }
      io::write(member, "ladder_amplitude", ladder_a.data(), ladder_a.size());
      io::write_string_attribute(member, "ladder_amplitude_unit", "d (drive amplitudes at which state changes are counted)");
      io::write(member, "ladder_contacts_opening", ladder_open.data(), ladder_open.size());
      io::write(member, "ladder_contacts_sliding", ladder_slide.data(), ladder_slide.size());
      io::write(member, "ladder_gaps_closing", ladder_close.data(), ladder_close.size());
      number(member, "solve_seconds", r.solve_seconds, "s");
      io::write_string_attribute(member, "problem", r.problem);
      io::write_string_attribute(member, "warning", r.warning);
    }
    io::Handle results = io::create_group(file, "results");
    const channel::DriveSettings& d = scene.drive;
    number(results, "omega_hat", e.members.empty() ? d.omega_hat : e.members.front().omega_hat, "1");
    number(results, "gamma_hat", e.members.empty() ? d.gamma_hat : e.members.front().gamma_hat, "1");
    number(results, "amplitude", d.amplitude, "d");
    number(results, "alpha_hat", e.alpha_hat, "Np per d");
    number(results, "sigma_alpha_hat", e.sigma_alpha_hat, "Np per d (standard error of the ensemble mean)");
    number(results, "c_hat", e.c_hat, "d sqrt(kappa/m)");
    number(results, "sigma_c_hat", e.sigma_c_hat, "d sqrt(kappa/m) (standard error of the ensemble mean)");
    number(results, "reflection", e.reflection, "1 (largest over the members; indicative only, see member_k)");
    io::write_attribute(results, "members", static_cast<std::int32_t>(e.members.size()));
    number(results, "solve_seconds", e.solve_seconds, "s");
    io::write_string_attribute(results, "problem", e.problem);
    io::write_string_attribute(results, "warning", e.warning);
  });
}

}  // namespace sedwave::forward::experiment
