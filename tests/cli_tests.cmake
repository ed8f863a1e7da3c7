# End-to-end tests of the nmesh command-line tool, run by ctest as
#   cmake -DNMESH=<path to nmesh> -DDATA=<bunny.ply> -DWORK=<scratch dir> -P cli_tests.cmake
# Each step runs the tool and checks its exit status and what it prints.
cmake_minimum_required(VERSION 3.16)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(failures 0)
set(passes 0)

# expect(NAME STATUS REGEX COMMAND...): run COMMAND; its exit status must be STATUS and its
# stdout+stderr must match REGEX ("" for anything).
function(expect name status regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(text "${out}${err}")
  if(NOT rc STREQUAL "${status}")
    message(SEND_ERROR "${name}: exit status ${rc}, expected ${status}\n${text}")
    math(EXPR failures "${failures} + 1")
  elseif(NOT regex STREQUAL "" AND NOT text MATCHES "${regex}")
    message(SEND_ERROR "${name}: output does not match '${regex}':\n${text}")
    math(EXPR failures "${failures} + 1")
  else()
    math(EXPR passes "${passes} + 1")
  endif()
  set(failures ${failures} PARENT_SCOPE)
  set(passes ${passes} PARENT_SCOPE)
endfunction()

# Help and usage errors.
expect(help 0 "reconstruct INPUT" ${NMESH} --help)
expect(reconstruct_help 0 "--vertices N" ${NMESH} reconstruct --help)
expect(eval_help 0 "DM\\(X,T\\)" ${NMESH} eval --help)
expect(info_help 0 "usage: nmesh info" ${NMESH} info --help)
expect(no_command 2 "no command given" ${NMESH})
expect(unknown_command 2 "unknown command 'frobnicate'" ${NMESH} frobnicate)
expect(no_output 2 "needs an output file" ${NMESH} reconstruct ${DATA})
expect(unknown_option 2 "unknown option --bogus" ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --bogus)
expect(bad_number 2 "--alpha-w needs a number" ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --alpha-w fast)
expect(bad_alpha 2 "invalid parameter alpha:" ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --alpha 1.5)
expect(bad_cvs 2 "invalid parameter cvs" ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --cvs 0)
expect(bad_topology 2 "invalid parameter topology: must be sphere, closed or open, got 'torus'"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --topology torus)
expect(topology_summary 0 "genus 0, 0 boundary loops \\(0 handles learnt\\)"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/topology.ply --vertices 600 --topology sphere)
# The bundled bunny at 1,000 vertices, seed 3, grown from the tetrahedron, goes back to a
# checkpoint once (--stats twist_retries).
expect(retry_summary 0 "learnt again from a checkpoint: 1 retries where part of the mesh had turned inside out"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/retry.ply --vertices 1000 --seed 3 --no-solid-start)
# The bunny walls a solid of genus 0 round only at 8 d, over its base holes: too plump a shape
# to start from (solid_start.h, kMaxShapeOffset), so it grows from the tetrahedron.
expect(solid_summary 0 "genus 0, 0 boundary loops \\(0 handles learnt\\)"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/solid.ply --vertices 1000 --seed 3 --stats ${WORK}/solid.json)
file(READ ${WORK}/solid.json solid_stats)
if(NOT solid_stats MATCHES "\"solid_genus\": 0,.*\"start_vertices\": 4,")
  message(SEND_ERROR "the bunny's solid: genus 0 read, the tetrahedron as the start expected")
  math(EXPR failures "${failures} + 1")
endif()
expect(small_target 2 "invalid parameter target_vertices" ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --vertices 3)
expect(output_is_input 2 "must not be the input" ${NMESH} reconstruct ${DATA} -o ${DATA})

# Runtime errors name the file.
expect(missing_input 1 "nosuch.ply" ${NMESH} reconstruct ${WORK}/nosuch.ply -o ${WORK}/x.ply)
expect(missing_dir 1 "missing/out.ply" ${NMESH} reconstruct ${DATA} -o ${WORK}/missing/out.ply --vertices 50 --quiet)
if(EXISTS ${WORK}/x.ply)
  message(SEND_ERROR "a failed run left ${WORK}/x.ply behind")
  math(EXPR failures "${failures} + 1")
endif()

# Reconstruct, then evaluate the result.
expect(reconstruct 0 "wrote .*mesh.ply: 1000 vertices, 1996 faces"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/mesh.ply --vertices 1000 --stats ${WORK}/stats.json --snapshots 100,500)
foreach(f mesh.ply mesh_100v.ply mesh_500v.ply stats.json)
  if(NOT EXISTS ${WORK}/${f})
    message(SEND_ERROR "reconstruct did not write ${f}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
file(READ ${WORK}/stats.json stats)
foreach(key vertices faces iterations splits collapses swaps_kept indexed_points seconds seconds_finish finish seed
        index_points_per_vertex dm_x_t hausdorff_rel)
  if(NOT stats MATCHES "\"${key}\": ")
    message(SEND_ERROR "stats.json has no key ${key}")
    math(EXPR failures "${failures} + 1")
  endif()
endforeach()
# The cloud's nearest-point index: the whole bunny by default (64 points per vertex would be
# 64,000), a sample of 2 points per vertex with --index-points 2.
if(NOT stats MATCHES "\"indexed_points\": 35947,")
  message(SEND_ERROR "stats.json: the default index does not hold the whole cloud")
  math(EXPR failures "${failures} + 1")
endif()
expect(index_points 0 "wrote .*sampled.ply: 1000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/sampled.ply --vertices 1000 --index-points 2 --stats ${WORK}/sampled.json)
file(READ ${WORK}/sampled.json sampled)
if(NOT sampled MATCHES "\"index_points_per_vertex\": 2, .*\"indexed_points\": 2000,")
  message(SEND_ERROR "stats.json: --index-points 2 did not index 2000 points")
  math(EXPR failures "${failures} + 1")
endif()
# --fit-rounds: recorded in the parameters, and DM(X,T) lower than without the fit. Seed 2: with
# seed 1 the stage's repair of the regularised (and fitted) mesh is undone, and the stage falls
# back on the learnt mesh, repaired, which the fit never touched.
expect(fit_reference 0 "wrote .*unfitted.ply: 1000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/unfitted.ply --vertices 1000 --seed 2 --no-solid-start --stats ${WORK}/unfitted.json)
file(READ ${WORK}/unfitted.json unfitted)
expect(fit_rounds 0 "wrote .*fitted.ply: 1000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/fitted.ply --vertices 1000 --seed 2 --no-solid-start --fit-rounds 2 --stats ${WORK}/fitted.json)
file(READ ${WORK}/fitted.json fitted)
string(REGEX MATCH "\"dm_x_t\": ([0-9.e+-]+)" unused "${unfitted}")
set(dm_default "${CMAKE_MATCH_1}")
string(REGEX MATCH "\"dm_x_t\": ([0-9.e+-]+)" unused "${fitted}")
set(dm_fitted "${CMAKE_MATCH_1}")
if(NOT fitted MATCHES "\"solid_start\": false.*\"fit_rounds\": 2," OR dm_default STREQUAL "" OR dm_fitted STREQUAL ""
   OR NOT dm_fitted LESS dm_default)
  message(SEND_ERROR "--fit-rounds 2: DM(X,T) ${dm_fitted} against ${dm_default} without the fit")
  math(EXPR failures "${failures} + 1")
endif()
# --threads: the same mesh, byte for byte, from one thread and from three; recorded in the
# parameters; a count out of range is a usage error, in reconstruct and in eval.
expect(threads_one 0 "" ${NMESH} reconstruct ${DATA} -o ${WORK}/threads1.ply --vertices 1000 --threads 1 --quiet)
expect(threads_three 0 "" ${NMESH} reconstruct ${DATA} -o ${WORK}/threads3.ply --vertices 1000 --threads 3 --quiet
  --stats ${WORK}/threads3.json)
file(READ ${WORK}/threads1.ply threads1 HEX)
file(READ ${WORK}/threads3.ply threads3 HEX)
file(READ ${WORK}/threads3.json threads3_stats)
if(NOT threads1 STREQUAL threads3 OR NOT threads3_stats MATCHES "\"threads\": 3}")
  message(SEND_ERROR "--threads 1 and --threads 3 wrote different meshes, or the stats lack the count")
  math(EXPR failures "${failures} + 1")
endif()
expect(bad_threads 2 "invalid parameter threads: must be in \\[0, 1024\\]"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/x.ply --threads 1025)
expect(eval_threads 0 "\"closed\": true" ${NMESH} eval ${DATA} ${WORK}/threads1.ply --json --threads 2)
expect(bad_eval_threads 2 "--threads: must be in \\[0, 1024\\]" ${NMESH} eval ${DATA} ${WORK}/threads1.ply --threads 5000)
# --surface-fit-rounds: recorded in the parameters; the mean distance from the points to the
# surface lower with the fit (on by default) than with --surface-fit-rounds 0 (both without the
# vertex exchange).
expect(surface_fit_off 0 "wrote .*unfit.ply: 2000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/unfit.ply --vertices 2000 --surface-fit-rounds 0 --exchange-passes 0
  --stats ${WORK}/unfit.json)
file(READ ${WORK}/unfit.json unfit)
expect(surface_fit_on 0 "wrote .*fit.ply: 2000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/fit.ply --vertices 2000 --exchange-passes 0 --stats ${WORK}/fit.json)
file(READ ${WORK}/fit.json fit)
string(REGEX MATCH "\"p2s_mean\": ([0-9.e+-]+)" unused "${unfit}")
set(p2s_unfit "${CMAKE_MATCH_1}")
string(REGEX MATCH "\"p2s_mean\": ([0-9.e+-]+)" unused "${fit}")
set(p2s_fit "${CMAKE_MATCH_1}")
if(NOT unfit MATCHES "\"surface_fit_rounds\": 0," OR p2s_unfit STREQUAL "" OR p2s_fit STREQUAL ""
   OR NOT p2s_fit LESS p2s_unfit)
  message(SEND_ERROR "the surface fit: mean point-to-surface ${p2s_fit} against ${p2s_unfit} without it")
  math(EXPR failures "${failures} + 1")
endif()
# --exchange-passes: recorded in the parameters; the mean distance from the points to the surface
# lower with the default 10 passes than with 0 (the bunny at 2,000 vertices: vertices moved from
# its flanks to its ears and feet).
expect(exchange_on 0 "wrote .*exchanged.ply: 2000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/exchanged.ply --vertices 2000 --stats ${WORK}/exchanged.json)
file(READ ${WORK}/exchanged.json exchanged)
string(REGEX MATCH "\"p2s_mean\": ([0-9.e+-]+)" unused "${exchanged}")
set(p2s_exchanged "${CMAKE_MATCH_1}")
if(NOT exchanged MATCHES "\"exchange_passes\": 10," OR NOT fit MATCHES "\"exchange_passes\": 0,"
   OR p2s_exchanged STREQUAL "" OR NOT p2s_exchanged LESS p2s_fit)
  message(SEND_ERROR "the vertex exchange: mean point-to-surface ${p2s_exchanged} against ${p2s_fit} without it")
  math(EXPR failures "${failures} + 1")
endif()
expect(quiet 0 "^$" ${NMESH} reconstruct ${DATA} -o ${WORK}/quiet.obj --vertices 200 --quiet)
expect(eval_json 0 "\"closed\": true.*\"genus\": 0" ${NMESH} eval ${DATA} ${WORK}/mesh.ply --json)
expect(eval_text 0 "dm_x_t" ${NMESH} eval ${DATA} ${WORK}/quiet.obj)
expect(info 0 "element vertex: 35947" ${NMESH} info ${DATA})
expect(info_mesh 0 "faces: 1996" ${NMESH} info ${WORK}/mesh.ply)
expect(info_mesh_topology 0
  "\ncomponents: 1\nclosed: yes\nmanifold: yes\nboundary loops: 0\neuler characteristic: 2\ngenus: 0\n$"
  ${NMESH} info ${WORK}/mesh.ply)
expect(eval_boundary 0 "\"genus\": 0,.*\"boundary_loops\": 0,\n  \"boundary_edges\": 0,"
  ${NMESH} eval ${DATA} ${WORK}/mesh.ply --json)

# The topology `info` reports for small meshes: a square tube open at both ends (OFF, four
# quads), a 4 x 4 grid of quads wrapped round both ways (OBJ, a torus) and two triangles sharing
# one vertex (a bow-tie).
file(WRITE ${WORK}/tube.off "OFF\n8 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
  "4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n")
expect(info_tube 0 "closed: no\nmanifold: yes\nboundary loops: 2 \\(8 edges, length 8\\)\neuler characteristic: 0\ngenus: 0\n"
  ${NMESH} info ${WORK}/tube.off)
set(torus_obj "")
foreach(i RANGE 3)
  foreach(j RANGE 3)
    string(APPEND torus_obj "v ${i} ${j} 0\n")
  endforeach()
endforeach()
foreach(i RANGE 3)
  foreach(j RANGE 3)
    math(EXPR a "${i} * 4 + ${j} + 1")
    math(EXPR b "(${i} + 1) % 4 * 4 + ${j} + 1")
    math(EXPR c "(${i} + 1) % 4 * 4 + (${j} + 1) % 4 + 1")
    math(EXPR d "${i} * 4 + (${j} + 1) % 4 + 1")
    string(APPEND torus_obj "f ${a} ${b} ${c} ${d}\n")
  endforeach()
endforeach()
file(WRITE ${WORK}/torus.obj "${torus_obj}")
expect(info_torus 0 "faces: 16\n.*closed: yes\nmanifold: yes\nboundary loops: 0\neuler characteristic: 0\ngenus: 1\n"
  ${NMESH} info ${WORK}/torus.obj)
file(WRITE ${WORK}/bow_tie.obj "v 0 0 0\nv 1 0 0\nv 1 1 0\nv -1 0 0\nv -1 -1 0\nf 1 2 3\nf 1 4 5\n")
expect(info_bow_tie 0 "manifold: no\nboundary loops: 2 \\(6 edges, [^\n]*\\)\neuler characteristic: 1\ngenus: - \\(not a manifold\\)\n"
  ${NMESH} info ${WORK}/bow_tie.obj)
expect(no_edge_swap 0 "0 swaps kept of 0 tried"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/nm.off --vertices 300 --no-edge-swap)
# The finishing stage runs by default and is reported; --no-finish skips it and changes the mesh.
expect(finish_default 0 "s learning [^\n]*, [0-9.]+ s finishing\n"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/finished.ply --vertices 1000)
expect(no_finish 0 "s learning \\([0-9.]+ M it/s\\)\n"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/unfinished.ply --vertices 1000 --no-finish)
file(SHA256 ${WORK}/finished.ply finished_sha)
file(SHA256 ${WORK}/unfinished.ply unfinished_sha)
if(finished_sha STREQUAL unfinished_sha)
  message(SEND_ERROR "--no-finish wrote the same mesh as the default")
  math(EXPR failures "${failures} + 1")
endif()
# --no-fold-guard: the paper's step 3, recorded in the statistics, and another learnt mesh.
expect(no_fold_guard 0 "wrote .*unguarded.ply: 1000 vertices"
  ${NMESH} reconstruct ${DATA} -o ${WORK}/unguarded.ply --vertices 1000 --no-finish --no-fold-guard
  --stats ${WORK}/unguarded.json)
file(READ ${WORK}/unguarded.json unguarded)
file(SHA256 ${WORK}/unguarded.ply unguarded_sha)
if(NOT unguarded MATCHES "\"fold_guard\": false.*\"moves_shortened\": 0,\n  \"folds_undone\": 0,"
   OR unguarded_sha STREQUAL unfinished_sha)
  message(SEND_ERROR "--no-fold-guard: not recorded, or the same mesh as with the guard")
  math(EXPR failures "${failures} + 1")
endif()

# Pictures.
expect(render_help 0 "usage: nmesh render" ${NMESH} render --help)
expect(render_no_output 2 "" ${NMESH} render ${WORK}/mesh.ply)
expect(render 0 "" ${NMESH} render ${WORK}/mesh.ply -o ${WORK}/mesh.png --size 256x192 --view iso --wireframe)
expect(render_error_map 0 "" ${NMESH} render ${WORK}/mesh.ply -o ${WORK}/error.png --size 128 --error-map ${DATA})
expect(render_missing_mesh 1 "nosuch.ply" ${NMESH} render ${WORK}/nosuch.ply -o ${WORK}/x.png)
expect(render_help_back_color 0 "--back-color RRGGBB" ${NMESH} render --help)
expect(render_bad_color 2 "option --color needs a colour RRGGBB in hexadecimal, got '12345G'"
  ${NMESH} render ${WORK}/mesh.ply -o ${WORK}/x.png --color 12345G)
expect(render_bad_back_color 2 "option --back-color needs a colour RRGGBB in hexadecimal, got 'orange'"
  ${NMESH} render ${WORK}/mesh.ply -o ${WORK}/x.png --back-color orange)
expect(render_short_back_color 2 "option --back-color needs a colour RRGGBB" ${NMESH} render ${WORK}/mesh.ply
  -o ${WORK}/x.png --back-color 12345)
expect(render_long_back_color 2 "option --back-color needs a colour RRGGBB" ${NMESH} render ${WORK}/mesh.ply
  -o ${WORK}/x.png --back-color "#1234567")
# One triangle, an open sheet: its front does not depend on --back-color, its back does.
file(WRITE ${WORK}/sheet.off "OFF\n3 1 0\n0 0 0\n1 0 0\n0.3 0.9 0\n3 0 1 2\n")
foreach(side front back)
  if(side STREQUAL "front")
    set(azimuth 0)
  else()
    set(azimuth 180)
  endif()
  foreach(color 102030 "#E0B090")
    string(REPLACE "#" "" name ${color})
    expect(render_${side}_${name} 0 "" ${NMESH} render ${WORK}/sheet.off -o ${WORK}/sheet_${side}_${name}.png
      --size 32 --azimuth ${azimuth} --back-color ${color})
    file(SHA256 ${WORK}/sheet_${side}_${name}.png sheet_${side}_${name})
  endforeach()
endforeach()
if(NOT sheet_front_102030 STREQUAL sheet_front_E0B090 OR sheet_back_102030 STREQUAL sheet_back_E0B090)
  message(SEND_ERROR "--back-color: the sheet's front changed with it, or its back did not")
  math(EXPR failures "${failures} + 1")
endif()
foreach(png mesh.png error.png)
  if(NOT EXISTS ${WORK}/${png})
    message(SEND_ERROR "render did not write ${png}")
    math(EXPR failures "${failures} + 1")
  else()
    # The PNG signature and the IHDR width of the first image (256 = 0x00000100).
    file(READ ${WORK}/${png} head LIMIT 24 HEX)
    if(NOT head MATCHES "^89504e470d0a1a0a0000000d49484452")
      message(SEND_ERROR "${png} is not a PNG file: ${head}")
      math(EXPR failures "${failures} + 1")
    endif()
  endif()
endforeach()
file(READ ${WORK}/mesh.png ihdr OFFSET 16 LIMIT 8 HEX)
if(NOT ihdr STREQUAL "00000100000000c0")
  message(SEND_ERROR "mesh.png is not 256x192: ${ihdr}")
  math(EXPR failures "${failures} + 1")
endif()

# The same seed writes the same bytes.
execute_process(COMMAND ${NMESH} reconstruct ${DATA} -o ${WORK}/again.ply --vertices 1000 --quiet)
file(SHA256 ${WORK}/mesh.ply first)
file(SHA256 ${WORK}/again.ply second)
if(NOT first STREQUAL second)
  message(SEND_ERROR "two runs with the same seed wrote different files")
  math(EXPR failures "${failures} + 1")
endif()

message("cli: ${passes} passed, ${failures} failed")
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} CLI checks failed")
endif()
