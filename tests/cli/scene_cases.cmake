# Command-line cases for input validation, restarts and outputs (docs/scenes.md, dem.md, tables.md):
# every bad value is refused when its file is read, naming file, line, key and accepted range; a
# restart or a resumed table refuses inputs that changed; no output replaces an input or is found
# unwritable only after the work. Files under data/scene/.
set(SCENE_DATA ${CLI_DATA}/scene)
set(SCENE_OUT ${CLI_OUT}/scene)  # outputs that a correct sedwave never writes (refused first)
set(SHIPPED_TABLES ${PROJECT_SOURCE_DIR}/data/tables)

# A fresh directory holding copies of FILES (from data/scene), for a case that runs IN it
# (expect.sh copies it again per run): cases that could write beside their inputs never touch the
# source tree, and no two cases share a directory.
function(scene_case_dir out_var name)
  set(dir ${SCENE_OUT}/in/${name})
  file(REMOVE_RECURSE ${dir})
  file(MAKE_DIRECTORY ${dir})
  foreach(f ${ARGN})
    file(COPY ${SCENE_DATA}/${f} DESTINATION ${dir})
  endforeach()
  set(${out_var} ${dir} PARENT_SCOPE)
endfunction()

# ---- Scene keys out of range (sedwave forward) ----------------------------------------------------
sedwave_cli_case(scene.negative_friction 1 [=[negative_friction\.toml:37: key 'contact.friction' = -0.3: accepted range \[0, inf\)]=] forward ${SCENE_DATA}/negative_friction.toml --out ${SCENE_OUT}/negative_friction.h5)
sedwave_cli_case(scene.negative_periods 1 [=[negative_periods\.toml:59: key 'drive.periods' = -3: accepted range \[0, 1000000\] periods]=] forward ${SCENE_DATA}/negative_periods.toml --out ${SCENE_OUT}/negative_periods.h5)
sedwave_cli_case(scene.negative_skip 1 [=[negative_skip\.toml:64: key 'drive.measurement.skip_layers' = -1: accepted range \[0, 1000000\] layers]=] forward ${SCENE_DATA}/negative_skip.toml --out ${SCENE_OUT}/negative_skip.h5)
sedwave_cli_case(scene.negative_settle 1 [=[negative_settle\.toml:65: key 'drive.measurement.settle_periods' = -2: accepted range \[0, 1000000\] periods]=] forward ${SCENE_DATA}/negative_settle.toml --out ${SCENE_OUT}/negative_settle.h5)
sedwave_cli_case(scene.poisson_one 1 [=[poisson_one\.toml:34: key 'contact.poisson_ratio' = 1: accepted range \(-1, 0\.5\]]=] forward ${SCENE_DATA}/poisson_one.toml --out ${SCENE_OUT}/poisson_one.h5)
sedwave_cli_case(scene.poisson_one_and_a_half 1 [=[poisson_one_and_a_half\.toml:34: key 'contact.poisson_ratio' = 1.5: accepted range \(-1, 0\.5\]]=] forward ${SCENE_DATA}/poisson_one_and_a_half.toml --out ${SCENE_OUT}/poisson_one_and_a_half.h5)
sedwave_cli_case(scene.absorbing_fraction_above_one 1 [=[absorbing_fraction_above_one\.toml:55: key 'drive.absorbing_fraction' = 1.2: accepted range \(0, 0\.9\] of the column]=] forward ${SCENE_DATA}/absorbing_fraction_above_one.toml --out ${SCENE_OUT}/absorbing_fraction_above_one.h5)
sedwave_cli_case(scene.zero_samples_per_period 1 [=[zero_samples_per_period\.toml:60: key 'drive.samples_per_period' = 0: accepted range \[4, 1000000\] samples per period]=] forward ${SCENE_DATA}/zero_samples_per_period.toml --out ${SCENE_OUT}/zero_samples_per_period.h5)
sedwave_cli_case(scene.time_step_above_stability 1 [=[time_step_above_stability\.toml:61: key 'drive.time_step_fraction' = 50: accepted range \(0, 0\.1\] of the binary collision time]=] forward ${SCENE_DATA}/time_step_above_stability.toml --out ${SCENE_OUT}/time_step_above_stability.h5)
sedwave_cli_case(scene.trillion_grains 1 [=[trillion_grains\.toml:13: key 'geometry.grains' = 1000000000000: accepted range \[1, 100000000\] grains]=] forward ${SCENE_DATA}/trillion_grains.toml --out ${SCENE_OUT}/trillion_grains.h5)
sedwave_cli_case(scene.grains_overflow_int 1 [=[grains_overflow_int\.toml:13: key 'geometry.grains' = 4294967496: accepted range \[1, 100000000\] grains]=] forward ${SCENE_DATA}/grains_overflow_int.toml --out ${SCENE_OUT}/grains_overflow_int.h5)
sedwave_cli_case(scene.negative_gamma_hat 1 [=[negative_gamma_hat\.toml:53: key 'drive.gamma_hat' = -0.1: accepted range \[0, inf\)]=] forward ${SCENE_DATA}/negative_gamma_hat.toml --out ${SCENE_OUT}/negative_gamma_hat.h5)
sedwave_cli_case(scene.zero_amplitude 1 [=[zero_amplitude\.toml:48: key 'drive.amplitude' = 0: accepted range \(0, 1\] d]=] forward ${SCENE_DATA}/zero_amplitude.toml --out ${SCENE_OUT}/zero_amplitude.h5)
sedwave_cli_case(scene.negative_seed 1 [=[negative_seed\.toml:16: key 'geometry.seed' = -1: accepted range \[0, 1000000000000000\]]=] forward ${SCENE_DATA}/negative_seed.toml --out ${SCENE_OUT}/negative_seed.h5)
sedwave_cli_case(scene.packing_fraction_too_high 1 [=[packing_fraction_too_high\.toml:17: key 'geometry.initial_packing_fraction' = 0.5: accepted range \(0, 0\.3\]]=] forward ${SCENE_DATA}/packing_fraction_too_high.toml --out ${SCENE_OUT}/packing_fraction_too_high.h5)
sedwave_cli_case(scene.negative_size_sd 1 [=[negative_size_sd\.toml:23: key 'geometry.sizes.sd' = -0.1: accepted range \[0, inf\) d]=] forward ${SCENE_DATA}/negative_size_sd.toml --out ${SCENE_OUT}/negative_size_sd.h5)
sedwave_cli_case(scene.contact_restitution_above_one 1 [=[contact_restitution_above_one\.toml:36: key 'contact.restitution' = 1.5: accepted range \(0, 1\]]=] forward ${SCENE_DATA}/contact_restitution_above_one.toml --out ${SCENE_OUT}/contact_restitution_above_one.h5)
sedwave_cli_case(scene.wall_roughness_too_large 1 [=[wall_roughness_too_large\.toml:29: key 'geometry.walls.roughness' = 0.8: accepted range \[0, 0\.5\] d]=] forward ${SCENE_DATA}/wall_roughness_too_large.toml --out ${SCENE_OUT}/wall_roughness_too_large.h5)
sedwave_cli_case(scene.too_many_extensions 1 [=[too_many_extensions\.toml:66: key 'drive.measurement.steady_extensions' = 1000: accepted range \[0, 100\]]=] forward ${SCENE_DATA}/too_many_extensions.toml --out ${SCENE_OUT}/too_many_extensions.h5)
sedwave_cli_case(scene.zero_pressure_tolerance 1 [=[zero_pressure_tolerance\.toml:44: key 'preparation.pressure_tolerance' = 0: accepted range \(0, 1\)]=] forward ${SCENE_DATA}/zero_pressure_tolerance.toml --out ${SCENE_OUT}/zero_pressure_tolerance.h5)
sedwave_cli_case(scene.compression_speed_too_fast 1 [=[compression_speed_too_fast\.toml:42: key 'preparation.compression_speed' = 5: accepted range \(0, 1\] d per binary collision time]=] forward ${SCENE_DATA}/compression_speed_too_fast.toml --out ${SCENE_OUT}/compression_speed_too_fast.h5)
sedwave_cli_case(scene.negative_density 1 [=[negative_density\.toml:15: key 'geometry.density' = -1: accepted range \(0, inf\)]=] forward ${SCENE_DATA}/negative_density.toml --out ${SCENE_OUT}/negative_density.h5)
sedwave_cli_case(scene.zero_layer_thickness 1 [=[zero_layer_thickness\.toml:63: key 'drive.measurement.layer_thickness' = 0: accepted range \(0, inf\) d]=] forward ${SCENE_DATA}/zero_layer_thickness.toml --out ${SCENE_OUT}/zero_layer_thickness.h5)
sedwave_cli_case(scene.width_below_largest_grain 1 [=[width_below_largest_grain\.toml:14: key 'geometry.width': must be at least the largest grain diameter]=] forward ${SCENE_DATA}/width_below_largest_grain.toml --out ${SCENE_OUT}/width_below_largest_grain.h5)
sedwave_cli_case(scene.size_min_above_mean 1 [=[size_min_above_mean\.toml:24: key 'geometry.sizes.min': must not exceed mean]=] forward ${SCENE_DATA}/size_min_above_mean.toml --out ${SCENE_OUT}/size_min_above_mean.h5)

# ---- Pore fluid ([fluid], sedwave forward; --fluid-*, sedwave dem) -------------------------------------
sedwave_cli_case(scene.fluid.zero_viscosity 1 [=[fluid_zero_viscosity\.toml:71: key 'fluid\.viscosity' = 0: accepted range \(0, 0\.1\] mu_hat = mu d / sqrt\(kappa m\)]=] forward ${SCENE_DATA}/fluid_zero_viscosity.toml --out ${SCENE_OUT}/fluid.h5)
sedwave_cli_case(scene.fluid.negative_viscosity 1 [=[fluid_negative_viscosity\.toml:71: key 'fluid\.viscosity' = -1e-05: accepted range \(0, 0\.1\]]=] forward ${SCENE_DATA}/fluid_negative_viscosity.toml --out ${SCENE_OUT}/fluid.h5)
sedwave_cli_case(scene.fluid.roughness_above_cutoff 1 [=[fluid_roughness_above_cutoff\.toml:73: key 'fluid\.cutoff': must exceed roughness \(0\.1\): accepted range \(0\.1, 1\] d]=] forward ${SCENE_DATA}/fluid_roughness_above_cutoff.toml --out ${SCENE_OUT}/fluid.h5)
sedwave_cli_case(scene.fluid.unknown_key 1 [=[fluid_unknown_key\.toml:74: key 'fluid\.density': unknown key]=] forward ${SCENE_DATA}/fluid_unknown_key.toml --out ${SCENE_OUT}/fluid.h5)
sedwave_cli_case(scene.fluid.missing_cutoff 1 [=[fluid_missing_cutoff\.toml:70: key 'fluid\.cutoff': missing \(required\)]=] forward ${SCENE_DATA}/fluid_missing_cutoff.toml --out ${SCENE_OUT}/fluid.h5)
sedwave_cli_case(scene.fluid.porosity_without_its_drag 1 [=[fluid_porosity_without_its_drag\.toml:75: key 'fluid\.porosity': is read by drag = "richardson_zaki" only]=] forward ${SCENE_DATA}/fluid_porosity_without_its_drag.toml --out ${SCENE_OUT}/fluid.h5)
# The long-wavelength limit computes tables only: a scene (and so `sedwave forward`) names a driven engine.
sedwave_cli_case(scene.forward.long_wavelength_refused 1 [=[long_wavelength_engine\.toml:4: key 'engine': must be one of linear, time_domain]=] forward ${SCENE_DATA}/long_wavelength_engine.toml --out ${SCENE_OUT}/long_wavelength_engine.h5)
sedwave_cli_case(scene.fluid.long_wavelength_refused 1 [=[fluid_table_scene\.toml: the long-wavelength limit is not defined with a pore fluid]=] table ${SCENE_DATA}/fluid_table_grid.toml --engine long_wavelength --out ${SCENE_OUT}/fluid_lw.h5)
set(DEM_COLUMN ${PROJECT_SOURCE_DIR}/tests/forward/dem/data/fcc_column.data)
sedwave_cli_case(scene.fluid.dem_negative_viscosity 2 [=[--fluid-viscosity: value -1 not in the accepted range \(0, inf\)]=] dem ${DEM_COLUMN} --steps 0 --kn 1000 --quiet --fluid-viscosity -1 --fluid-roughness 0.001 --fluid-cutoff 0.1)
sedwave_cli_case(scene.fluid.dem_roughness_above_cutoff 1 [=[--fluid-cutoff 0\.01: accepted range \(--fluid-roughness, inf\) = \(0\.1, inf\)]=] dem ${DEM_COLUMN} --steps 0 --kn 1000 --quiet --fluid-viscosity 1 --fluid-roughness 0.1 --fluid-cutoff 0.01)
sedwave_cli_case(scene.fluid.dem_runs_in_a_fluid 0 [=[in a fluid \(viscosity 0\.01, roughness 0\.001, cutoff 0\.1, lubrication, drag stokes, density 0\.5\)]=] dem ${DEM_COLUMN} --steps 50 --kn 1000 --gravity 0,0,-1 --fluid-viscosity 0.01 --fluid-roughness 0.001 --fluid-cutoff 0.1 --fluid-drag stokes --fluid-density 0.5)
sedwave_cli_case(scene.fluid.dem_missing_viscosity 1 [=[--fluid-viscosity is required with any --fluid-\* option]=] dem ${DEM_COLUMN} --steps 0 --kn 1000 --quiet --fluid-roughness 0.001 --fluid-cutoff 0.1)

# ---- Grid files (sedwave table) --------------------------------------------------------------------
sedwave_cli_case(scene.grid.points_overflow 1 [=[grid_points_overflow\.toml:3: key 'omega_hat\.points' = 10000000000: accepted range \[2, 100000\] points]=]
  table ${SCENE_DATA}/grid_points_overflow.toml --out ${SCENE_OUT}/grid_points_overflow.h5)
sedwave_cli_case(scene.grid.negative_ranks_per_point 1 [=[grid_negative_ranks_per_point\.toml:3: key 'ranks_per_point' = -1: accepted range \[1, 1000000\] ranks]=]
  table ${SCENE_DATA}/grid_negative_ranks_per_point.toml --out ${SCENE_OUT}/grid_negative_ranks_per_point.h5)
sedwave_cli_case(scene.grid.restitution_one 1 [=[grid_restitution_one\.toml:4: key 'restitution\[0\]' = 1: accepted range \(0, 1\)]=]
  table ${SCENE_DATA}/grid_restitution_one.toml --out ${SCENE_OUT}/grid_restitution_one.h5)
sedwave_cli_case(scene.grid.negative_omega 1 [=[grid_negative_omega\.toml:3: key 'omega_hat\[1\]' = -1: accepted range \(0, inf\)]=]
  table ${SCENE_DATA}/grid_negative_omega.toml --out ${SCENE_OUT}/grid_negative_omega.h5)
sedwave_cli_case(scene.grid.scene_out_of_range 1 [=[negative_friction\.toml:37: key 'contact\.friction' = -0\.3: accepted range]=]
  table ${SCENE_DATA}/grid_bad_scene.toml --out ${SCENE_OUT}/grid_bad_scene.h5)

# ---- LAMMPS data files (sedwave dem) ---------------------------------------------------------------
sedwave_cli_case(scene.dem_data.velocity_of_unknown_atom 1 [=[dem_velocity_unknown_id\.data:18: Velocities entry for atom id 7, which is not in the Atoms section]=]
  dem ${SCENE_DATA}/dem_velocity_unknown_id.data --steps 0 --kn 1000 --quiet)
sedwave_cli_case(scene.dem_data.inverted_box 1 [=[dem_inverted_box\.data:6: xlo 4 and xhi 0: the box must have finite, positive extent]=]
  dem ${SCENE_DATA}/dem_inverted_box.data --steps 0 --kn 1000 --quiet)
sedwave_cli_case(scene.dem_data.atom_type_zero 1 [=[dem_type_zero\.data:12: atom type 0: accepted range \[1, ]=]
  dem ${SCENE_DATA}/dem_type_zero.data --steps 0 --kn 1000 --quiet)
sedwave_cli_case(scene.dem_data.nan_coordinate 1 [=[dem_nan_coordinate\.data:13: coordinates must be finite]=]
  dem ${SCENE_DATA}/dem_nan_coordinate.data --steps 0 --kn 1000 --quiet)

# ---- sedwave dem options out of range (usage errors) ----------------------------------------------
sedwave_cli_case(scene.dem_options.poisson_above_half 2 [=[--poisson: value 1\.5 not in the accepted range \(-1, 0\.5\]]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 0 --young 1000 --poisson 1.5 --quiet)
sedwave_cli_case(scene.dem_options.restitution_above_one 2 [=[--restitution: value 1\.2 not in the accepted range \(0, 1\]]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 0 --kn 1000 --restitution 1.2 --quiet)
sedwave_cli_case(scene.dem_options.negative_time_step 2 [=[--dt: value -0\.001 not in the accepted range \(0, inf\)]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 0 --kn 1000 --dt -0.001 --quiet)

# ---- sedwave dem contact laws: every part selectable; options of parts not chosen refused ---------
sedwave_cli_case(scene.dem_contact.hertz_mindlin_rolling 0 [=[dem: 2 grains, hertz\+mindlin\+rolling, time step]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 10 --law hertz --young 1000 --restitution 0.9 --tangential mindlin
  --friction 0.5 --rolling constant_torque --rolling-friction 0.05)
sedwave_cli_case(scene.dem_contact.hooke_coulomb_tanh 0 [=[dem: 2 grains, hooke\+coulomb_tanh, time step]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 10 --kn 1000 --tangential coulomb_tanh --friction 0.5
  --tanh-velocity-scale 100)
sedwave_cli_case(scene.dem_contact.kt_without_tangential_law 1 [=[--kt does not apply to hooke]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 0 --kn 1000 --kt 100 --quiet)
sedwave_cli_case(scene.dem_contact.unknown_law 2 [=[--tangential: .*mindlin]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 0 --kn 1000 --tangential sticky --quiet)

# ---- DEM restarts refuse changed inputs ------------------------------------------------------------
# The setup writes a checkpoint at step 100 (a wiggled floor); each case restarts from it. Refused
# restarts write nothing, and the allowed one is already at its last step, so the cases may run in
# any order.
set(RESTART ${SCENE_OUT}/restart)
file(MAKE_DIRECTORY ${RESTART})
set(RESTART_RUN --kn 1000 --restitution 0.9 --checkpoint ${RESTART}/checkpoint.h5 --quiet)
sedwave_cli_case(scene.restart.setup 0 [=[.*]=] dem ${SCENE_DATA}/fcc_column.data --steps 100 --wiggle 2:z:0.001:10 ${RESTART_RUN})
set_tests_properties(cli.scene.restart.setup PROPERTIES FIXTURES_SETUP scene_checkpoint)
sedwave_cli_case(scene.restart.changed_kn 1 [=[--kn: 1000 in the checkpoint, 1200 now]=]
  dem ${SCENE_DATA}/fcc_column.data --steps 200 --wiggle 2:z:0.001:10 --restart
  --kn 1200 --restitution 0.9 --checkpoint ${RESTART}/checkpoint.h5 --quiet)
sedwave_cli_case(scene.restart.changed_wiggle 1 [=[--wiggle: 2:z:0\.001:10 in the checkpoint, 2:z:0\.002:10 now]=]
  dem ${SCENE_DATA}/fcc_column.data --steps 200 --wiggle 2:z:0.002:10 --restart ${RESTART_RUN})
sedwave_cli_case(scene.restart.one_grain_fewer 1 [=[data file: hash [0-9a-f]{16} in the checkpoint, hash [0-9a-f]{16} now]=]
  dem ${SCENE_DATA}/fcc_column_one_fewer.data --steps 200 --wiggle 2:z:0.001:10 --restart ${RESTART_RUN})
sedwave_cli_case(scene.restart.allow_changed_inputs 0 [=[restarting from .*checkpoint\.h5 at step 100]=]
  dem ${SCENE_DATA}/fcc_column.data --steps 100 --wiggle 2:z:0.001:10 --restart --allow-changed-inputs
  --kn 1200 --restitution 0.9 --checkpoint ${RESTART}/checkpoint.h5)
set_tests_properties(cli.scene.restart.changed_kn cli.scene.restart.changed_wiggle cli.scene.restart.one_grain_fewer
  cli.scene.restart.allow_changed_inputs PROPERTIES FIXTURES_REQUIRED scene_checkpoint)

# ---- Resumed tables refuse another packing ---------------------------------------------------------
set(RESUME ${SCENE_OUT}/resume)
file(MAKE_DIRECTORY ${RESUME})
set(RESUME_RUN table ${SCENE_DATA}/table_resume_grid.toml --out ${RESUME}/table.h5 --engine long_wavelength --quiet)
# --allow-changed-inputs: a table left by an older build is resumed, never refused, by the setup.
file(REMOVE ${RESUME}/table.h5 ${RESUME}/table.h5.journal)
sedwave_cli_case(scene.table.resume_setup 0 [=[table .*table\.h5: 2 points]=]
  ${RESUME_RUN} --packing ${SHIPPED_TABLES}/linear_w3.packing.h5 --allow-changed-inputs)
set_tests_properties(cli.scene.table.resume_setup PROPERTIES FIXTURES_SETUP scene_table)
sedwave_cli_case(scene.table.resume_with_other_packing 1 [=[packing: hash [0-9a-f]{16} in the table, [0-9a-f]{16} now]=]
  ${RESUME_RUN} --packing ${SHIPPED_TABLES}/linear_w3.packing.member1.h5)
set_tests_properties(cli.scene.table.resume_with_other_packing PROPERTIES FIXTURES_REQUIRED scene_table)

# A --out that names a file of another kind is refused before any work and left as it was (only a
# damaged table is set aside and rebuilt).
scene_case_dir(dir table_out_not_a_table table_resume_grid.toml linear_one.toml not_a_table.h5)
sedwave_cli_case(scene.table.out_not_a_table 1 [=[cannot write table not_a_table\.h5: the file exists and is not a sedwave dispersion table \(it is not an HDF5 file\)]=]
  IN ${dir} table table_resume_grid.toml --out not_a_table.h5 --engine long_wavelength --quiet)

# ---- Outputs never replace inputs, and are checked writable before the work ------------------------
scene_case_dir(dir out_is_scene tiny.toml)
sedwave_cli_case(scene.output.forward_out_is_scene 2 [=[--out: output tiny\.toml would overwrite the input tiny\.toml]=]
  IN ${dir} forward tiny.toml --out tiny.toml)
scene_case_dir(dir out_is_packing tiny.toml table_transposed.h5)
sedwave_cli_case(scene.output.forward_out_is_packing 2 [=[--out: output table_transposed\.h5 would overwrite the input table_transposed\.h5]=]
  IN ${dir} forward tiny.toml --packing table_transposed.h5 --out table_transposed.h5)
scene_case_dir(dir packing_out_is_packing tiny.toml table_transposed.h5)
sedwave_cli_case(scene.output.forward_packing_out_is_packing 2 [=[--packing-out: output table_transposed\.h5 would overwrite the input]=]
  IN ${dir} forward tiny.toml --packing table_transposed.h5 --packing-out table_transposed.h5 --out run.h5)
sedwave_cli_case(scene.output.forward_out_unwritable 1 [=[--out /dev/null/run\.h5: cannot create directory /dev/null]=]
  forward ${SCENE_DATA}/tiny.toml --out /dev/null/run.h5)
sedwave_cli_case(scene.output.forward_packing_out_unwritable 1 [=[--packing-out /dev/null/packing\.h5: cannot create directory]=]
  forward ${SCENE_DATA}/tiny.toml --out ${SCENE_OUT}/tiny_run.h5 --packing-out /dev/null/packing.h5)
scene_case_dir(dir table_out_is_grid table_resume_grid.toml linear_one.toml)
sedwave_cli_case(scene.output.table_out_is_grid 2 [=[--out: output table_resume_grid\.toml would overwrite the input]=]
  IN ${dir} table table_resume_grid.toml --out table_resume_grid.toml --engine long_wavelength
  --packing ${SHIPPED_TABLES}/linear_w3.packing.h5)
sedwave_cli_case(scene.output.table_out_unwritable 1 [=[--out /dev/null/table\.h5: cannot create directory]=]
  table ${SCENE_DATA}/table_resume_grid.toml --out /dev/null/table.h5 --engine long_wavelength
  --packing ${SHIPPED_TABLES}/linear_w3.packing.h5)
scene_case_dir(dir merge_out_is_member table_transposed.h5)
sedwave_cli_case(scene.output.merge_out_is_member 2 [=[--out: output table_transposed\.h5 would overwrite the input]=]
  IN ${dir} merge table_transposed.h5 --out table_transposed.h5)
scene_case_dir(dir dem_final_is_data dem_two_grains.data)
sedwave_cli_case(scene.output.dem_final_is_data 2 [=[--final: output dem_two_grains\.data would overwrite the input]=]
  IN ${dir} dem dem_two_grains.data --steps 0 --kn 1000 --final dem_two_grains.data)
sedwave_cli_case(scene.output.dem_checkpoint_unwritable 1 [=[--checkpoint /dev/null/checkpoint\.h5: cannot create directory]=]
  dem ${SCENE_DATA}/dem_two_grains.data --steps 10 --kn 1000 --checkpoint /dev/null/checkpoint.h5 --every 5)
scene_case_dir(dir dem_dump_is_h5md dem_two_grains.data)
sedwave_cli_case(scene.output.dem_two_outputs_one_file 2 [=[--dump and --h5md both name trajectory]=]
  IN ${dir} dem dem_two_grains.data --steps 0 --kn 1000 --dump trajectory --dump-every 1 --h5md trajectory --h5md-every 1)

# ---- Tables are read by shape and format version ----------------------------------------------------
sedwave_cli_case(scene.table.transposed_results 1 [=[table_transposed\.h5: dataset /results/alpha_hat has shape \[3, 2\], expected \[2, 3\]]=]
  show ${SCENE_DATA}/table_transposed.h5)
sedwave_cli_case(scene.table.wrong_format_version 1 [=[table_format_version_2\.h5: format_version 2, expected 1]=]
  show ${SCENE_DATA}/table_format_version_2.h5)
# A table says what its sigma includes: one packing's noise, or an ensemble's standard error.
sedwave_cli_case(show.one_packing_sigma_is_said 0 "# sigma: one packing: .*does NOT include packing-to-packing"
  show ${PROJECT_SOURCE_DIR}/data/tables/thesis_w3_small.h5)
sedwave_cli_case(show.ensemble_sigma_is_said 0 "# sigma: standard error of the mean over 5 independent packings"
  show ${PROJECT_SOURCE_DIR}/data/tables/field_w3_long_wavelength.h5)
