# `sedwave reflect` (docs/reflection.md): a seabed of sediment models, its reflection coefficient and
# the files propagation codes read; layers named per layer; models without a density and malformed
# layer settings refused by name.
set(REFLECT_OUT --out ${CLI_OUT}/reflect_never)

# (expect.sh matches one line: one case per line that must be there)
sedwave_cli_case(models.lists_the_shear_wave 0 "^  shear wave: k_s = \\(omega / sqrt\\(gamma_s/rho_0\\)\\)" models grain-shearing)
sedwave_cli_case(models.edfm_has_no_shear_wave 0 "^  shear wave: none" models edfm)
sedwave_cli_case(reflect.grain_shearing_halfspace 0 "^  half-space grain-shearing +1000 +1783\\.99 "
  reflect --frequency 1000 --angle-step 5 --out ${CLI_OUT}/reflect_gs)
sedwave_cli_case(reflect.layer_and_files 0 "^refl_cli\\.brc: BELLHOP bottom reflection table, 19 grazing angles"
  IN ${CLI_OUT} reflect --layer edfm --set l1.thickness=2 --set l1.porosity=0.7 --frequency 3000 --angle-step 5
  --band 0.3333 --band-samples 5 --out reflect_layer --brc refl_cli.brc)
sedwave_cli_case(reflect.env_file 0 "^refl_cli\\.env: Acoustics Toolbox environment \\(blocks 1-6\\), 2 frequencies, attenuation unit 'Q'"
  IN ${CLI_OUT} reflect --frequency 1000,2000 --angle-step 10 --out reflect_env --env refl_cli.env --water-depth 50
  --env-unit Q)
sedwave_cli_case(reflect.layer_without_thickness 2 "layer l1 \\(--layer edfm\\): give --set l1.thickness=METRES"
  reflect --layer edfm --frequency 1000 ${REFLECT_OUT})
sedwave_cli_case(reflect.setting_for_a_missing_layer 2 "--set l2.porosity=0.5: layer l2 does not exist \\(1 --layer given\\)"
  reflect --layer edfm --set l1.thickness=1 --set l2.porosity=0.5 --frequency 1000 ${REFLECT_OUT})
sedwave_cli_case(reflect.layer_unknown_parameter 2 "unknown parameter 'porosty'"
  reflect --layer edfm --set l1.thickness=1 --set l1.porosty=0.5 --frequency 1000 ${REFLECT_OUT})
sedwave_cli_case(reflect.dry_frame_has_no_density 1 "half-space: model 'lattice' fixes no bulk density"
  reflect --model lattice --kappa 1e6 --d 3e-4 --gamma 5 --frequency 1000 ${REFLECT_OUT})
sedwave_cli_case(reflect.brc_needs_one_frequency 2 "--brc is for one --frequency"
  reflect --frequency 1000,2000 ${REFLECT_OUT} --brc ${CLI_OUT}/never.brc)
sedwave_cli_case(reflect.env_needs_water_depth 2 "--env needs --water-depth"
  reflect --frequency 1000 ${REFLECT_OUT} --env ${CLI_OUT}/never.env)
# A band of bottom loss over posterior draws; its columns name the half-space's and the layers' parameters.
sedwave_cli_case(reflect.posterior_band 0 "^posterior: bottom loss quantiles over 3 draws of .*draws.csv"
  reflect --layer edfm --set l1.thickness=2 --frequency 1000 --angle-step 10 --out ${CLI_OUT}/reflect_posterior
  --posterior ${CLI_DATA}/reflect/draws.csv)
sedwave_cli_case(reflect.posterior_unknown_column 1 "unknown_column.csv: column 'porosty' names no parameter of this seabed"
  reflect --frequency 1000 ${REFLECT_OUT} --posterior ${CLI_DATA}/reflect/unknown_column.csv)
# A fitted seabed from invert's fit.json: its values (porosity 0.44: 0.44 x 1005 + 0.56 x 2730 = 1971.0 kg/m^3).
sedwave_cli_case(reflect.from_fit 0 "^  half-space grain-shearing +1000 .* 1971\\.0$"
  reflect --from-fit ${CLI_DATA}/reflect/gs_fit.json --frequency 1000 --angle-step 10 --out ${CLI_OUT}/reflect_fit)
sedwave_cli_case(reflect.from_fit_of_another_model 2 "--from-fit .*gs_fit.json: a fit of model 'grain-shearing', the half-space is 'edfm'"
  reflect --model edfm --from-fit ${CLI_DATA}/reflect/gs_fit.json --frequency 1000 ${REFLECT_OUT})
# A seabed no sediment can be (gamma_p 2500 times the reference sand's: c_p 32 km/s) is flagged, exit 3.
sedwave_cli_case(reflect.flags_an_impossible_speed 3 "^! half-space grain-shearing at 1000 Hz: c_p = 3[0-9]+ m/s outside \\[100, 20000\\] m/s"
  reflect --set gamma_p=1e12 --frequency 1000 --angle-step 10 --out ${CLI_OUT}/reflect_flagged)

# Layered seabeds as one model (docs/reflection.md, "Layered seabeds"): a layer's thickness has no
# typical value; a layered spec needs a layer and a half-space; its layers are not given twice.
sedwave_cli_case(reflect.layered_needs_thickness 2 "model 'layered:edfm\\+edfm': give l1.thickness"
  reflect --model layered:edfm+edfm --frequency 1000 --out ${CLI_OUT}/layered_no_thickness)
sedwave_cli_case(reflect.layered_and_layer_option 2 "--layer: model 'layered:edfm\\+edfm' is layered itself"
  reflect --model layered:edfm+edfm --layer edfm --set l1.thickness=1 --frequency 1000 --out ${CLI_OUT}/layered_twice)
sedwave_cli_case(synthesize.layered_without_halfspace 1 "model 'layered:edfm': a layered seabed names at least one layer and its half-space"
  synthesize --model layered:edfm --from 1e3 --to 4e3 --grazing-angles 10 --out ${CLI_OUT}/never_layered.csv)
sedwave_cli_case(synthesize.layered_needs_thickness 1 "give l1.thickness \\(--set NAME=VALUE\\)"
  synthesize --model layered:edfm+edfm --from 1e3 --to 4e3 --grazing-angles 10 --out ${CLI_OUT}/never_thickness.csv)
sedwave_cli_case(synthesize.reflection_only_needs_angles 2 "--reflection-only needs --grazing-angles"
  synthesize --model edfm --from 1e3 --to 4e3 --reflection-only --out ${CLI_OUT}/never_angles.csv)
sedwave_cli_case(synthesize.grazing_angle_beyond_90 2 "--grazing-angles"
  synthesize --model edfm --from 1e3 --to 4e3 --grazing-angles 10,95 --out ${CLI_OUT}/never_95.csv)
sedwave_cli_case(invert.layered_dry_frame_layer 1 "layer l1: model 'lattice' fixes no bulk density"
  invert ${CMAKE_CURRENT_SOURCE_DIR}/data/invert/bottom_loss_edfm.csv --model layered:lattice+edfm
  --set l1.thickness=1 --fit porosity --method ceres --no-plot --out ${CLI_OUT}/layered_dry)
# The water above the seabed has a physical range (fresh water near freezing to hot brine); so has the
# synthetic bottom loss's noise.
sedwave_cli_case(reflect.water_speed_huge 2 "--water-speed: 1e308 is outside the accepted range \\[1300, 1800\\]"
  reflect --model edfm --frequency 1000 --water-speed 1e308 --out ${CLI_OUT}/water_huge)
sedwave_cli_case(reflect.water_density_nan 2 "--water-density"
  reflect --model edfm --frequency 1000 --water-density nan --out ${CLI_OUT}/water_nan)
sedwave_cli_case(synthesize.water_speed_huge 2 "--water-speed: 1e308 is outside the accepted range \\[1300, 1800\\]"
  synthesize --model edfm --from 1e3 --to 4e3 --grazing-angles 10 --water-speed 1e308 --out ${CLI_OUT}/never_water.csv)
sedwave_cli_case(synthesize.water_density_huge 2 "--water-density: 1e308 is outside the accepted range \\[950, 1300\\]"
  synthesize --model edfm --from 1e3 --to 4e3 --grazing-angles 10 --water-density 1e308 --out ${CLI_OUT}/never_rho.csv)
sedwave_cli_case(synthesize.bottom_loss_sigma_huge 2 "--bottom-loss-sigma: 1e308 is outside the accepted range"
  synthesize --model edfm --from 1e3 --to 4e3 --grazing-angles 10 --bottom-loss-sigma 1e308 --out ${CLI_OUT}/never_sigma.csv)
