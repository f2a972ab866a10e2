# Command-line cases of `sedwave interface` (docs/interface.md): bad scene values are refused naming
# file, line, key and accepted range; a tiny scene runs and closes its energy balance. Files under
# data/interface/.
set(INTERFACE_DATA ${CLI_DATA}/interface)
set(INTERFACE_OUT ${CLI_OUT}/interface)
file(MAKE_DIRECTORY ${INTERFACE_OUT})
sedwave_cli_case(interface.bad_poisson 1 [=[bad_poisson\.toml:4: key 'plate\.poisson_ratio' = 0\.6: accepted range \(-1, 0\.5\]]=] interface ${INTERFACE_DATA}/bad_poisson.toml --out ${INTERFACE_OUT}/never.h5)
# Poisson's ratio and the contact keys take the DEM scenes' bounds (one declaration).
sedwave_cli_case(interface.bad_grain_poisson 1 [=[bad_grain_poisson\.toml:11: key 'packing\.poisson_ratio' = -1: accepted range \(-1, 0\.5\]]=] interface ${INTERFACE_DATA}/bad_grain_poisson.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.negative_friction 1 [=[negative_friction\.toml:13: key 'contact\.friction' = -0\.1: accepted range \[0, inf\)]=] interface ${INTERFACE_DATA}/negative_friction.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.misspelt_key 1 [=[misspelt_key\.toml:10: key 'packing\.colums': unknown key]=] interface ${INTERFACE_DATA}/misspelt_key.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.packing_wider_than_plate 1 [=[packing_too_wide\.toml:[0-9]+: \[packing\]: 'x_offset' \(default\): the packing \(0\.1525 m wide\) must lie over the plate \(0\.024 m\)]=] interface ${INTERFACE_DATA}/packing_too_wide.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.output_over_scene 2 [=[--out: output .*would overwrite the input]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_DATA}/tiny.toml)
sedwave_cli_case(interface.tiny_run 0 [=[largest share in the plate [0-9.]+. energy balance within [0-9.]+e-0[6-9] of the input]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_OUT}/tiny.h5)
sedwave_cli_case(interface.participation_ratio 0 [=[energy is shared by [0-9.]+ of 6 grains at the end \(participation ratio. 3 at the start\)]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_OUT}/tiny_participation.h5)
sedwave_cli_case(interface.precompression_needs_a_clamped_edge 1 [=[unsupported_precompression\.toml:13: key 'packing\.precompression': a static load needs a clamped plate edge]=] interface ${INTERFACE_DATA}/unsupported_precompression.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.direct_strike 0 [=[direct strike on the plate's edge over x = 0\.00575 \.\. 0\.02075 m with the energy of 3 beads]=] interface ${INTERFACE_DATA}/tiny.toml --direct --out ${INTERFACE_OUT}/direct.h5)
sedwave_cli_case(interface.direct_strike_coarse_samples 0 [=[note: the arrival \(the direct pulse.s front\) is read from samples every 4e-08 s, coarser than a tenth of the mesh.s transit time h/c_L = 3\.71e-07 s: set run\.output_interval below 3\.71e-08 s]=] interface ${INTERFACE_DATA}/tiny.toml --direct --out ${INTERFACE_OUT}/direct_coarse.h5)
# The paper's rigid-layer contact: a value outside the list, a bead between nodes, a tiny run.
sedwave_cli_case(interface.bad_plate_contact 1 [=[bad_plate_contact\.toml:3: key 'plate\.contact': must be one of interpolated, rigid_layers]=] interface ${INTERFACE_DATA}/bad_plate_contact.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.rigid_layers_between_nodes 1 [=[rigid_layers_between_nodes\.toml:7: key 'plate\.contact': .*grain 0 at x = 0\.00575 m lies between the nodes at 0\.003 and 0\.006 m]=] interface ${INTERFACE_DATA}/rigid_layers_between_nodes.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.rigid_layers_run 0 [=[energy balance within [0-9.]+e-0[6-9] of the input]=] interface ${INTERFACE_DATA}/rigid_layers.toml --out ${INTERFACE_OUT}/rigid_layers.h5)
# The monolithic plate's edge impulse: a load beyond any solid, and a precompression with no beads.
sedwave_cli_case(interface.huge_line_load 1 [=[huge_line_load\.toml:4: key 'drive\.line_load' = 1000000000000: accepted range \(0, 100000000\] N/m]=] interface ${INTERFACE_DATA}/huge_line_load.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.edge_impulse_precompression 1 [=[edge_impulse_precompression\.toml:6: key 'packing\.precompression': drive\.kind = "edge_impulse" strikes the plate alone]=] interface ${INTERFACE_DATA}/edge_impulse_precompression.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.edge_impulse_run 0 [=[uniform impulse of 20000 N/m for 1e-06 s on the plate's edge over x = 0\.00575 \.\. 0\.02075 m \(no beads\)]=] interface ${INTERFACE_DATA}/edge_impulse.toml --out ${INTERFACE_OUT}/edge_impulse.h5)
sedwave_cli_case(interface.speed_with_edge_impulse 1 [=[--speed overrides a velocity drive. this scene's drive\.kind is edge_impulse]=] interface ${INTERFACE_DATA}/edge_impulse.toml --speed 1 --out ${INTERFACE_OUT}/never.h5)
# The paper's scheme: a wrong name, tolerances out of range or without it, a pulse it cannot take, a tiny run.
sedwave_cli_case(interface.bad_scheme 1 [=[bad_scheme\.toml:4: key 'run\.scheme': must be one of multirate, newmark_rk4, velocity_verlet]=] interface ${INTERFACE_DATA}/bad_scheme.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tiny_iteration_reltol 1 [=[tiny_iteration_reltol\.toml:5: key 'run\.iteration_reltol' = 1e-20: accepted range \[1e-15, 0\.01\]]=] interface ${INTERFACE_DATA}/tiny_iteration_reltol.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_iteration_abstol 1 [=[huge_iteration_abstol\.toml:5: key 'run\.iteration_abstol' = 1000000000: accepted range \[0, 1000000\] N]=] interface ${INTERFACE_DATA}/huge_iteration_abstol.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.reltol_without_newmark 1 [=[reltol_without_newmark\.toml:4: key 'run\.iteration_reltol': sets the newmark_rk4 scheme's iteration, and run\.scheme is velocity_verlet]=] interface ${INTERFACE_DATA}/reltol_without_newmark.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.edge_impulse_newmark 1 [=[edge_impulse_newmark\.toml:9: key 'run\.scheme': newmark_rk4 takes no pulse on the plate]=] interface ${INTERFACE_DATA}/edge_impulse_newmark.toml --out ${INTERFACE_OUT}/never.h5)
# The multirate scheme: a tiny run that closes its balance, no fixed step (key or option), its outer
# tolerance in range and only with it.
sedwave_cli_case(interface.multirate_run 0 [=[multirate: [0-9]+ plate steps, [0-9.]+ grain steps each]=] interface ${INTERFACE_DATA}/multirate.toml --out ${INTERFACE_OUT}/multirate.h5)
sedwave_cli_case(interface.multirate_balance 0 [=[energy balance within [0-9.]+e-0[5-9] of the input]=] interface ${INTERFACE_DATA}/multirate.toml --out ${INTERFACE_OUT}/multirate_balance.h5)
sedwave_cli_case(interface.multirate_fixed_step 1 [=[multirate_fixed_step\.toml:5: key 'run\.fixed_step': the multirate scheme \(run\.scheme\) chooses its own outer steps and substeps: it takes no fixed step]=] interface ${INTERFACE_DATA}/multirate_fixed_step.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.multirate_fixed_step_option 2 [=[usage error: the multirate scheme \(run\.scheme\) chooses its own steps: it takes no fixed step \(--fixed-step\)]=] interface ${INTERFACE_DATA}/multirate.toml --fixed-step 1e-9 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_plate_tolerance 1 [=[huge_plate_tolerance\.toml:5: key 'run\.plate_tolerance' = 1\.5: accepted range \(0, 0\.5\]]=] interface ${INTERFACE_DATA}/huge_plate_tolerance.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.zero_plate_tolerance 1 [=[zero_plate_tolerance\.toml:5: key 'run\.plate_tolerance' = 0: accepted range \(0, 0\.5\]]=] interface ${INTERFACE_DATA}/zero_plate_tolerance.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.negative_plate_tolerance 1 [=[negative_plate_tolerance\.toml:5: key 'run\.plate_tolerance' = -0\.1: accepted range \(0, 0\.5\]]=] interface ${INTERFACE_DATA}/negative_plate_tolerance.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.nan_plate_tolerance 1 [=[nan_plate_tolerance\.toml:5: key 'run\.plate_tolerance': must be finite]=] interface ${INTERFACE_DATA}/nan_plate_tolerance.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.overflow_plate_tolerance 1 [=[overflow_plate_tolerance\.toml:5: key 'run\.plate_tolerance' = 1e\+308: accepted range \(0, 0\.5\]]=] interface ${INTERFACE_DATA}/overflow_plate_tolerance.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.plate_tolerance_without_multirate 1 [=[plate_tolerance_without_multirate\.toml:4: key 'run\.plate_tolerance': sets the multirate scheme's outer step, and run\.scheme is velocity_verlet]=] interface ${INTERFACE_DATA}/plate_tolerance_without_multirate.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.newmark_rk4_run 0 [=[newmark_rk4: [0-9]+ fixed-point iterations \([0-9.]+ a step, at most [0-9]+\), [0-9]+ factorisations]=] interface ${INTERFACE_DATA}/newmark_rk4.toml --out ${INTERFACE_OUT}/newmark_rk4.h5)
sedwave_cli_case(interface.newmark_below_roundoff 1 [=[did not converge in 100 iterations at t = .*the iteration's tolerances \(0 N, 1e-15 relative\) lie below what round-off]=] interface ${INTERFACE_DATA}/newmark_below_roundoff.toml --out ${INTERFACE_OUT}/never.h5)

# Side walls: a side that does not exist, a wall key without walls, values out of range, walls off the
# plate, walls with no beads, a static load on rows that only walls could hold; and a packing precompressed between them,
# whose plate carries the load of its five top beads (5 x 5 N).
sedwave_cli_case(interface.bad_wall_sides 1 [=[bad_wall_sides\.toml:14: key 'walls\.sides': must be one of both, left, none, right]=] interface ${INTERFACE_DATA}/bad_wall_sides.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.wall_key_without_walls 1 [=[wall_key_without_walls\.toml:14: key 'walls\.gap': sets the side walls, and walls\.sides is none]=] interface ${INTERFACE_DATA}/wall_key_without_walls.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_wall_gap 1 [=[huge_wall_gap\.toml:15: key 'walls\.gap' = 1e\+308: accepted range \[0, 10\] m]=] interface ${INTERFACE_DATA}/huge_wall_gap.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.wall_beyond_plate 1 [=[wall_beyond_plate\.toml:15: key 'walls\.gap': the walls \(at x = -0\.00175 m and 0\.03775 m\) must stand over the plate]=] interface ${INTERFACE_DATA}/wall_beyond_plate.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_wall_modulus 1 [=[huge_wall_modulus\.toml:15: key 'walls\.youngs_modulus' = 1e\+308: accepted range \[1000, 2000000000000\] Pa]=] interface ${INTERFACE_DATA}/huge_wall_modulus.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.bad_wall_poisson 1 [=[bad_wall_poisson\.toml:15: key 'walls\.poisson_ratio' = 0\.6: accepted range \(-1, 0\.5\]]=] interface ${INTERFACE_DATA}/bad_wall_poisson.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.negative_wall_friction 1 [=[negative_wall_friction\.toml:15: key 'walls\.friction' = -0\.1: accepted range \[0, inf\)]=] interface ${INTERFACE_DATA}/negative_wall_friction.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.precompression_needs_walls 1 [=[precompression_without_walls\.toml:12: key 'packing\.precompression': a static load spreads a packing of more than one row \(chain\) sideways.*walls\.sides = "both"]=] interface ${INTERFACE_DATA}/precompression_without_walls.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.edge_impulse_walls 1 [=[edge_impulse_walls\.toml:3: key 'walls\.sides': drive\.kind = "edge_impulse" strikes the plate alone: no beads to hold]=] interface ${INTERFACE_DATA}/edge_impulse_walls.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.precompressed_between_walls 0 [=[relaxed in [0-9]+ steps. at rest the plate carries 25 N, the side walls [0-9.]+ N \(left\) and [0-9.]+ N \(right\)]=] interface ${INTERFACE_DATA}/walls.toml --out ${INTERFACE_OUT}/walls.h5)

# Bad input of every kind, each refused before the run with its cause (docs/interface.md, "Limits
# and budgets"). Outputs: none may replace the scene or another output of the same run.
file(MAKE_DIRECTORY ${INTERFACE_OUT}/csv_scene)
configure_file(${INTERFACE_DATA}/tiny.toml ${INTERFACE_OUT}/csv_scene/energies.csv COPYONLY)
sedwave_cli_case(interface.csv_over_scene 2 [=[--csv: output .*energies\.csv would overwrite the input]=] interface ${INTERFACE_OUT}/csv_scene/energies.csv --csv ${INTERFACE_OUT}/csv_scene --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.csv_over_run_file 2 [=[--out and --csv both name .*energies\.csv]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_OUT}/both/energies.csv --csv ${INTERFACE_OUT}/both)
# Values that overflowed the solver's integer conversions or allocations.
sedwave_cli_case(interface.huge_packing_density 1 [=[huge_packing_density\.toml:[0-9]+: key 'packing\.density' = 1e\+308: accepted range \[1, 30000\] kg/m\^3]=] interface ${INTERFACE_DATA}/huge_packing_density.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_precompression 1 [=[key 'packing\.precompression' = 1e\+308: accepted range \[0, 1000000\] N]=] interface ${INTERFACE_DATA}/huge_precompression.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_mesh 1 [=[would hold about [0-9.e+]+ GB \(1e\+10 plate nodes.*budget of 4 GB.*--max-memory]=] interface ${INTERFACE_DATA}/huge_mesh.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_packing 1 [=[would hold about [0-9.e+]+ GB \(.*1e\+10 grains.*--max-memory]=] interface ${INTERFACE_DATA}/huge_packing.toml --out ${INTERFACE_OUT}/never.h5)
string(REPEAT "[" 100000 open)
string(REPEAT "]" 100000 close)
file(WRITE ${INTERFACE_OUT}/deep_probes.toml "[run]\nduration = 4e-5\nprobe_x = ${open}0.01${close}\n")
sedwave_cli_case(interface.deeply_nested_probes 1 [=[deep_probes\.toml:3: syntax error: arrays or inline tables nested deeper than 64 levels]=] interface ${INTERFACE_OUT}/deep_probes.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.integer_beyond_64_bits 1 [=[key 'plate\.elements_x' = 99999999999999999999: accepted range \[1, 100000\]]=] interface ${INTERFACE_DATA}/overflowing_elements.toml --out ${INTERFACE_OUT}/never.h5)
# Runs that would not end in any useful time: estimated and refused, with the budget and its option.
sedwave_cli_case(interface.strike_beyond_hertz 1 [=[strike at 1e\+04 m/s .* would press a bead .* of its radius: Hertz's small-strain contact holds below 0\.1]=] interface ${INTERFACE_DATA}/tiny.toml --speed 1e4 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tiny_tolerance_option 1 [=[about [0-9.]+e\+0?[89] steps .*above the budget of 1e\+07 steps.*--max-steps]=] interface ${INTERFACE_DATA}/tiny.toml --tolerance 1e-6 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tiny_fixed_step_option 1 [=[about 4e\+295 steps .*--max-steps]=] interface ${INTERFACE_DATA}/tiny.toml --fixed-step 1e-300 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_run_duration 1 [=[key 'run\.duration' = 1e\+308: accepted range \(0, 1000\] s]=] interface ${INTERFACE_DATA}/huge_run_duration.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.long_run 1 [=[about [0-9.]+e\+(09|10) steps .*--max-steps]=] interface ${INTERFACE_DATA}/long_run.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.long_strip 1 [=[about [0-9.]+e\+06 steps \(step [0-9.e-]+ s .* plate [0-9.]+e-11 s.*above the budget of 1e\+06 steps]=] interface ${INTERFACE_DATA}/long_strip.toml --max-steps 1e6 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.fine_sampling 1 [=[4e\+08 samples.*(--max-memory|--max-steps)]=] interface ${INTERFACE_DATA}/fine_sampling.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tiny_interval 1 [=[4e\+295 samples]=] interface ${INTERFACE_DATA}/tiny_interval.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.sharp_friction 1 [=[Coulomb-tanh [0-9.]+e-1[4-7] s.*--max-steps]=] interface ${INTERFACE_DATA}/sharp_friction.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tiny_tolerance_key 1 [=[about [0-9.]+e\+30[0-9] steps .*--max-steps]=] interface ${INTERFACE_DATA}/tiny_tolerance.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tiny_fixed_step_key 1 [=[about 4e\+10 steps .*--max-steps]=] interface ${INTERFACE_DATA}/tiny_fixed_step.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.light_plate 1 [=[key 'plate\.density' = 0\.000785: accepted range \[1, 30000\] kg/m\^3]=] interface ${INTERFACE_DATA}/light_plate.toml --out ${INTERFACE_OUT}/never.h5)
# Nonsense that ran to exit 0.
sedwave_cli_case(interface.huge_pulse_duration 1 [=[key 'drive\.duration' = 1e\+308: accepted range \(0, 1000\] s]=] interface ${INTERFACE_DATA}/long_pulse.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.pulse_outlasts_run 1 [=[key 'drive\.duration': the pulse \(0\.001 s\) outlasts the run]=] interface ${INTERFACE_DATA}/pulse_outlasts_run.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_lift 1 [=[key 'packing\.lift' = 1e\+308: accepted range \[0, 10\] m]=] interface ${INTERFACE_DATA}/huge_lift.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_plate_density 1 [=[key 'plate\.density' = 1e\+308: accepted range]=] interface ${INTERFACE_DATA}/huge_plate_density.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.huge_fixed_step 1 [=[key 'run\.fixed_step' = 1e\+308: accepted range \[0, 4e-05\] s]=] interface ${INTERFACE_DATA}/huge_fixed_step.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.infinite_fixed_step 2 [=[--fixed-step: 'inf' is not a finite number]=] interface ${INTERFACE_DATA}/tiny.toml --fixed-step inf --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.contact_wider_than_plate 1 [=[contact radius of [0-9.e-]+ m, above half the plate's thickness \(plate\.thickness / 2 = 5e-06 m\)]=] interface ${INTERFACE_DATA}/thin_plate.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.fixed_step_beyond_plate_limit 1 [=[fixed step 1\.07e-06 s .* exceeds the plate's stability limit 2/omega_max = 3\.57e-07 s]=] interface ${INTERFACE_DATA}/unstable_fixed_step.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.unstable_run_stopped 1 [=[energy balance is off by [0-9.e+]+ times the input energy .*the fixed step .* exceeds a contact's limit]=] interface ${INTERFACE_DATA}/fixed_step_over_contacts.toml --out ${INTERFACE_OUT}/never.h5)
# Checked before the run, not after it.
sedwave_cli_case(interface.out_is_a_device 1 [=[--out: .*/dev/null]=] interface ${INTERFACE_DATA}/tiny.toml --out /dev/null)
sedwave_cli_case(interface.out_in_missing_unwritable_directory 1 [=[--out /proc/no/such/run\.h5: cannot create directory]=] interface ${INTERFACE_DATA}/tiny.toml --out /proc/no/such/run.h5)
sedwave_cli_case(interface.csv_unwritable 1 [=[--csv /proc/no/such/energies\.csv: cannot create directory]=] interface ${INTERFACE_DATA}/tiny.toml --csv /proc/no/such --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.csv_is_a_file 1 [=[--csv .*bad_poisson\.toml/energies\.csv: cannot create directory]=] interface ${INTERFACE_DATA}/tiny.toml --csv ${INTERFACE_DATA}/bad_poisson.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tolerance_with_fixed_step 2 [=[--tolerance sets the adaptive step's theta, and this run has a fixed step \(--fixed-step\)]=] interface ${INTERFACE_DATA}/tiny.toml --fixed-step 1e-8 --tolerance 0.1 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.tolerance_with_scene_fixed_step 2 [=[this run has a fixed step \(run\.fixed_step in .*fixed_step_scene\.toml\)]=] interface ${INTERFACE_DATA}/fixed_step_scene.toml --tolerance 0.1 --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.option_as_out 2 [=[--out: '--quiet' looks like an option]=] interface ${INTERFACE_DATA}/tiny.toml --out --quiet)
add_test(NAME cli.interface.out_is_a_fifo
  COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 1 [=[--out: .*a FIFO]=] -- bash -c
          "rm -f \"$1\" && mkfifo \"$1\" && exec \"$0\" interface \"$2\" --out \"$1\""
          $<TARGET_FILE:sedwave> ${INTERFACE_OUT}/fifo.h5 ${INTERFACE_DATA}/tiny.toml)
set_tests_properties(cli.interface.out_is_a_fifo PROPERTIES TIMEOUT 150)
# A long run (100000 x 1 elements: about 3e6 steps over 2e5 nodes) announces its estimate and prints
# its progress with the time left within 30 s, then is stopped.
add_test(NAME cli.interface.long_run_announces
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/interface_announces.sh $<TARGET_FILE:sedwave>
          ${INTERFACE_DATA}/long_strip.toml ${INTERFACE_OUT}/long_strip.h5 30)
set_tests_properties(cli.interface.long_run_announces PROPERTIES TIMEOUT 150)
# 40 000 probes: on one line (toml11 scans a value's whole line, so one line of n values parses in
# n^2) the file is refused at once with the fix; over many lines it parses in linear time.
string(REPEAT "0.01, " 40000 probes)
file(WRITE ${INTERFACE_OUT}/probes_one_line.toml "[run]\nduration = 4e-5\nprobe_x = [${probes}]\n")
sedwave_cli_case(interface.probes_on_one_line 1 [=[probes_one_line\.toml:3: syntax error: a line longer than 65536 characters \(break a long array over several lines]=] interface ${INTERFACE_OUT}/probes_one_line.toml --out ${INTERFACE_OUT}/never.h5)
string(REPEAT "0.01,\n" 40000 probes)
file(WRITE ${INTERFACE_OUT}/probes_many_lines.toml "[run]\nduration = 4e-5\nprobe_x = [\n${probes}]\nmisspelt = 1\n")
sedwave_cli_case(interface.probes_on_many_lines 1 [=[probes_many_lines\.toml:40005: key 'run\.misspelt': unknown key]=] interface ${INTERFACE_OUT}/probes_many_lines.toml --out ${INTERFACE_OUT}/never.h5)
# An empty value (CMake drops "" from a command's arguments: passed through bash).
foreach(empty speed csv)
  add_test(NAME cli.interface.empty_${empty}
    COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "--${empty}: ('' is not a number|an empty path names no file)" -- bash -c
            "exec \"$0\" interface \"$1\" --${empty} '' --out \"$2\""
            $<TARGET_FILE:sedwave> ${INTERFACE_DATA}/tiny.toml ${INTERFACE_OUT}/never.h5)
  set_tests_properties(cli.interface.empty_${empty} PROPERTIES TIMEOUT 150)
endforeach()
sedwave_cli_case(interface.out_names_a_missing_directory 1 [=[--out .*/missing_run_dir/: names a directory. give a file name]=] interface ${INTERFACE_DATA}/tiny.toml --out ${INTERFACE_OUT}/missing_run_dir/)
# Every contact law of the DEM between grains, with the DEM scenes' keys ([contact] law, tangential,
# rolling and their keys); the grain-plate contact stays Hertz with Coulomb-tanh.
sedwave_cli_case(interface.contact_laws 0 [=[largest share in the plate [0-9.]+. energy balance within [0-9.]+e-0[5-9] of the input]=] interface ${INTERFACE_DATA}/contact_laws.toml --out ${INTERFACE_OUT}/contact_laws.h5)
sedwave_cli_case(interface.unknown_law 1 [=[unknown_law\.toml:13: key 'contact\.law': must be one of hertz, hooke]=] interface ${INTERFACE_DATA}/unknown_law.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.kn_for_hertz 1 [=[kn_for_hertz\.toml:13: key 'contact\.kn': unknown key]=] interface ${INTERFACE_DATA}/kn_for_hertz.toml --out ${INTERFACE_OUT}/never.h5)
sedwave_cli_case(interface.history_with_newmark 1 [=[history_newmark\.toml:24: key 'run\.scheme': newmark_rk4 takes no grain contact with a tangential history]=] interface ${INTERFACE_DATA}/history_newmark.toml --out ${INTERFACE_OUT}/never.h5)
