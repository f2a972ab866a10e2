// The figures of a posterior study and of a ranking, composed from the single plots.
#include <string>
#include <vector>

#include "sedwave/plot/plot.hpp"

namespace sedwave::plot {

using namespace inversion;

std::vector<std::string> draw_posterior_plots(const std::filesystem::path& dir, const PosteriorStudy& study,
                                              const FitResult& best, const ObservationSet& data) {
  CornerFiles corner;
  for (const std::string& name : study.posterior.sample_names) {
    corner.best_fit.push_back(best.fitted.spec[best.fitted.index_of(name)].value);
  }
  return {draw_corner_plot(dir, study.posterior.sample_names, study.posterior.sample_units, corner).message,
          draw_predictive_plot(dir, "posterior_predictive", "sedwave posterior band: " + best.model,
                               data.water_sound_speed.has_value(), best, {{best.model, "posterior_predictive.csv"}},
                               "posterior_residuals.csv")
              .message};
}

std::vector<std::string> draw_ranking_plots(const std::filesystem::path& dir, const Ranking& ranking,
                                            const ObservationSet& data) {
  std::vector<BandFile> bands;
  for (std::size_t i = 0; i < ranking.models.size(); ++i) {
    bands.push_back({ranking.models[i].model, ranking_file("predictive", i, ranking.models[i].label)});
  }
  std::vector<std::string> messages;
  messages.push_back(draw_predictive_plot(dir, "predictive", "sedwave compare: posterior bands",
                                          data.water_sound_speed.has_value(), ranking.models.front().fit, bands,
                                          "predictive_residuals.csv")
                         .message);
  const auto best = static_cast<std::size_t>(ranking.order.front());
  const ComparedModel& m = ranking.models[best];
  const auto [names, units] = sample_columns(m);
  std::vector<double> best_fit;
  for (int i : m.fit.fitted.free_indices()) best_fit.push_back(m.fit.fitted.spec[static_cast<std::size_t>(i)].value);
  const CornerFiles files{ranking_file("samples", best, m.label), "corner_best",
                          "posterior of " + m.model + " (ranked first)", best_fit};
  messages.push_back(draw_corner_plot(dir, names, units, files).message);
  return messages;
}

}  // namespace sedwave::plot
