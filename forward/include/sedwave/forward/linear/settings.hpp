#pragma once
// Settings of the linear-response engine, as a scene's [linear] section states them
// (docs/scenes.md). Plain data: scenes hold it without depending on the engine.
namespace sedwave::forward::linear {

struct LinearSettings {
  /// Independently generated packings (seeds seed, seed + 1, ...): a single disordered channel
  /// scatters, so results are the mean over the ensemble with its standard error.
  int ensemble = 1;
  /// Gaps narrower than this [mean diameters] are checked for closing; with a pore fluid, gaps up to
  /// its lubrication cut-off are listed too (their squeeze films).
  double gap_search = 1e-2;
  /// Fraction of contacts opening plus gaps closing (of all contacts) during the cycle above which a
  /// result warns, and above which it is refused (the time-domain engine is then the right one).
  double warn_state_changes = 0.01;
  double refuse_state_changes = 0.1;
};

}  // namespace sedwave::forward::linear
