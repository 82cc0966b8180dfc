# One test per study manifest, integration_study_<name>: manifests/quickstart.json and every
# manifests/*-smoke.json (a new smoke manifest is picked up at the next build: CONFIGURE_DEPENDS),
# so that `ctest -j2` runs two manifests at a time instead of all of them in series.
#
# Each runs the runner with 2 workers (engines are single-threaded), so at most 4 engines share the
# 2 cores. With one worker per test, the independent replicas of a manifest run one after the other
# even when the other ctest slot is idle: nu_nb_switching-smoke spends most of its time in two DMC
# replicas, and became the tail of the suite that way.
#
# COST: without timings from an earlier run (a fresh build directory), ctest starts the tests of
# highest COST first. The manifests' COST is the runner's cost estimate of their engine jobs in
# seconds, from the tools' own cost models (--describe), so it is computed once the tools are built
# (manifest_costs/), and the longest manifests start first while the short tests fill in.
#
# Default suite budget: under 10 minutes on 2 cores. A smoke manifest that would break it gets the
# label `slow` (scripts/test --all) by being named in _slow_smoke_manifests. The two named here
# (73 s and 60 s on a fresh clone, 2026-12-07, when the suite took 635 s) run the same tools as
# smoke manifests that stay in the default suite (lb_ellipsoid_sweep-smoke: config, lb,
# lb-diffusion; dpd_rod_diffusion-smoke: config, dpd, msd), so every tool is still run by default.
set(_slow_smoke_manifests lb_sphere_radius_sweep-smoke dpd_sphere_diffusion-smoke)
set(_workers 2)
file(GLOB _smoke_manifests CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/manifests/*-smoke.json)
set(_manifests ${CMAKE_SOURCE_DIR}/manifests/quickstart.json ${_smoke_manifests})
foreach(_manifest ${_manifests})
  get_filename_component(_study ${_manifest} NAME_WLE)
  set(_slow)
  if(_study IN_LIST _slow_smoke_manifests)
    set(_slow SLOW)
  endif()
  anisodyn_add_script_test(study_${_study} study_manifests.py ${_slow} ARGS ${_study} ${_workers})
endforeach()
add_subdirectory(manifest_costs)  # after the tests: ctest reads a subdirectory's files last
