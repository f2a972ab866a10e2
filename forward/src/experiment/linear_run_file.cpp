#include "sedwave/forward/experiment/linear_run_file.hpp"

#include "../io/hdf5.hpp"
#include "run_file_parts.hpp"

namespace sedwave::forward::experiment {

using namespace linear;  // the file holds the linear engine's results

void write_linear_run_file(const std::filesystem::path& path, const ChannelScene& scene,
                           const std::vector<channel::PreparationReport>& preparations, const EnsembleResult& e) {
  h5::write_file_atomically(path, [&](hid_t file) {
    write_run_header(file, scene.text);
    h5::write_string_attribute(file, "engine", "linear");
    for (std::size_t k = 0; k < e.members.size(); ++k) {
      const LinearResult& r = e.members[k];
      h5::Handle member = h5::create_group(file, "member_" + std::to_string(k));
      h5::write_attribute(member, "seed", static_cast<std::int64_t>(scene.geometry.seed + k));
      if (k < preparations.size()) {
        h5::Handle packing = h5::create_group(member, "packing");
        write_stats(packing, preparations[k]);
      }
      h5::write(member, "layer_z", r.layer_z.data(), r.layer_z.size());
      h5::write_string_attribute(member, "layer_z_unit", "d, from the driven wall's mean surface");
      h5::write(member, "layer_grains", r.layer_grains.data(), r.layer_grains.size());
      std::vector<double> re, im;
      for (const auto& u : r.layer_field) {
        re.push_back(u.real());
        im.push_back(u.imag());
      }
      h5::write(member, "layer_field_real", re.data(), re.size());
      h5::write(member, "layer_field_imag", im.data(), im.size());
      h5::write_string_attribute(member, "layer_field_unit",
                                 "wall amplitude A; mean displacement along the drive axis is Re(U exp(i omega t))");
      write_fit(member, r.fit);
      number(member, "two_wave_alpha_hat", r.waves.alpha, "Np per d");
      number(member, "two_wave_k_hat", r.waves.k, "rad per d");
      number(member, "reflection", r.waves.reflection, "1 (at the absorbing layer's start; indicative only: in a disordered channel with alpha L >> 1 scattering noise dominates it)");
      h5::write_attribute(member, "contacts", r.state_changes.contacts);
      h5::write_attribute(member, "contacts_opening", r.state_changes.opening);
      h5::write_attribute(member, "contacts_sliding", r.state_changes.sliding);
      h5::write_attribute(member, "gaps", r.state_changes.gaps);
      h5::write_attribute(member, "gaps_closing", r.state_changes.closing);
      std::vector<double> ladder_a;
      std::vector<std::int64_t> ladder_open, ladder_slide, ladder_close;
      for (const StateChanges& c : r.amplitude_ladder) {
        ladder_a.push_back(c.amplitude);
        ladder_open.push_back(c.opening);
        ladder_slide.push_back(c.sliding);
        ladder_close.push_back(c.closing);
      }
      h5::write(member, "ladder_amplitude", ladder_a.data(), ladder_a.size());
      h5::write_string_attribute(member, "ladder_amplitude_unit", "d (drive amplitudes at which state changes are counted)");
      h5::write(member, "ladder_contacts_opening", ladder_open.data(), ladder_open.size());
      h5::write(member, "ladder_contacts_sliding", ladder_slide.data(), ladder_slide.size());
      h5::write(member, "ladder_gaps_closing", ladder_close.data(), ladder_close.size());
      number(member, "solve_seconds", r.solve_seconds, "s");
      h5::write_string_attribute(member, "problem", r.problem);
      h5::write_string_attribute(member, "warning", r.warning);
    }
    h5::Handle results = h5::create_group(file, "results");
    const channel::DriveSettings& d = scene.drive;
    number(results, "omega_hat", e.members.empty() ? d.omega_hat : e.members.front().omega_hat, "1");
    number(results, "gamma_hat", e.members.empty() ? d.gamma_hat : e.members.front().gamma_hat, "1");
    number(results, "amplitude", d.amplitude, "d");
    number(results, "alpha_hat", e.alpha_hat, "Np per d");
    number(results, "sigma_alpha_hat", e.sigma_alpha_hat, "Np per d (standard error of the ensemble mean)");
    number(results, "c_hat", e.c_hat, "d sqrt(kappa/m)");
    number(results, "sigma_c_hat", e.sigma_c_hat, "d sqrt(kappa/m) (standard error of the ensemble mean)");
    number(results, "reflection", e.reflection, "1 (largest over the members; indicative only, see member_k)");
    h5::write_attribute(results, "members", static_cast<std::int32_t>(e.members.size()));
    number(results, "solve_seconds", e.solve_seconds, "s");
    h5::write_string_attribute(results, "problem", e.problem);
    h5::write_string_attribute(results, "warning", e.warning);
  });
}

}  // namespace sedwave::forward::experiment
