# Robustness of the nmesh command-line tool, run by ctest as
#   cmake -DNMESH=<path to nmesh> -DDATA=<bunny.ply> -DWORK=<scratch dir> -P cli_robustness.cmake
# Bad files get exit status 1 and one line naming the file; degenerate clouds behave as README.md
# says; a run stopped by SIGINT or SIGTERM leaves no output and no temporary file; the input is
# never modified. Every run of the tool here also goes through LeakSanitizer in the sanitizer build.
#
# Not tested: an input the user may not read. Permission bits do not stop root, so that check runs
# only when the tests do not run as root; the unreadable case otherwise tested is a path through a
# regular file ("file.ply/x", ENOTDIR).
cmake_minimum_required(VERSION 3.16)

file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
set(failures 0)
set(passes 0)
set(known 0)

# Checks that fail today because of a defect in the tool, each described where it is listed. Such
# a check is reported but does not fail the test; once it passes, the test fails until the name is
# removed from this list (so a fix is noticed).
set(KNOWN_BUGS
)

macro(fail msg)
  message(SEND_ERROR "${msg}")
  math(EXPR failures "${failures} + 1")
endmacro()

# Inside a function: hands the check counters back to the caller.
macro(return_counts)
  set(failures ${failures} PARENT_SCOPE)
  set(passes ${passes} PARENT_SCOPE)
  set(known ${known} PARENT_SCOPE)
endmacro()

# verdict(NAME OK MESSAGE): count a check, honouring KNOWN_BUGS.
function(verdict name ok msg)
  if(name IN_LIST KNOWN_BUGS)
    if(ok)
      message(SEND_ERROR "${name}: passes now; remove it from KNOWN_BUGS")
      math(EXPR failures "${failures} + 1")
    else()
      message("${name}: known defect, still present: ${msg}")
      math(EXPR known "${known} + 1")
    endif()
  elseif(ok)
    math(EXPR passes "${passes} + 1")
  else()
    message(SEND_ERROR "${name}: ${msg}")
    math(EXPR failures "${failures} + 1")
  endif()
  return_counts()
endfunction()

# check(NAME MESSAGE CONDITION...): count a check passing when if(CONDITION) holds; variables in
# the condition are named, not expanded, so that their values cannot break the condition apart.
function(check _c_name _c_msg)
  if(${ARGN})
    verdict(${_c_name} TRUE "")
  else()
    verdict(${_c_name} FALSE "${_c_msg}")
  endif()
  return_counts()
endfunction()

# expect(NAME STATUS REGEX COMMAND...): run COMMAND (at most 120 s); its exit status must be
# STATUS and its stdout+stderr must match REGEX ("" for anything). Sets `text` in the caller.
function(expect name status regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  set(text "${out}${err}" PARENT_SCOPE)
  set(text "${out}${err}")
  if(NOT rc STREQUAL "${status}")
    verdict(${name} FALSE "exit status ${rc}, expected ${status}\n${text}")
  elseif(NOT regex STREQUAL "" AND NOT text MATCHES "${regex}")
    verdict(${name} FALSE "output does not match '${regex}':\n${text}")
  else()
    verdict(${name} TRUE "")
  endif()
  return_counts()
endfunction()

# bad_file(NAME REGEX): `nmesh reconstruct` and `nmesh info` on ${WORK}/NAME both exit with 1 and
# print exactly one line, "nmesh: error: <path>: ...", matching REGEX; no output file appears.
function(bad_file name regex)
  set(path "${WORK}/${name}")
  string(REGEX REPLACE "([][+.*()^$?|\\])" "\\\\\\1" quoted "${path}")
  set(one_line "^nmesh: error: ${quoted}: [^\n]*${regex}[^\n]*\n$")
  expect(reconstruct_${name} 1 "${one_line}" ${NMESH} reconstruct ${path} -o ${WORK}/out.ply --vertices 50 --quiet)
  expect(info_${name} 1 "${one_line}" ${NMESH} info ${path})
  if(EXISTS ${WORK}/out.ply)
    fail("${name}: a failed run left out.ply behind")
    file(REMOVE ${WORK}/out.ply)
  endif()
  return_counts()
endfunction()

file(SHA256 ${DATA} data_sha_before)
file(COPY ${DATA} DESTINATION ${WORK})
get_filename_component(data_name ${DATA} NAME)
set(bunny ${WORK}/${data_name})  # a copy, for the checks that could harm their input

# ---- 1. Bad files ----------------------------------------------------------------------------
set(ply_header "ply\nformat ascii 1.0\n")
set(xyz3 "property float x\nproperty float y\nproperty float z\n")
file(WRITE ${WORK}/empty.ply "")
file(WRITE ${WORK}/header_only.ply "${ply_header}element vertex 1\n${xyz3}end_header\n")
file(WRITE ${WORK}/no_end_header.ply "${ply_header}element vertex 1\n${xyz3}")
file(WRITE ${WORK}/format.ply "ply\nformat binary_middle_endian 1.0\nelement vertex 1\n${xyz3}end_header\n1 2 3\n")
file(WRITE ${WORK}/version.ply "ply\nformat ascii 2.0\nelement vertex 1\n${xyz3}end_header\n1 2 3\n")
file(WRITE ${WORK}/points.dat "1 2 3\n4 5 6\n")
file(WRITE ${WORK}/fewer.ply
  "${ply_header}element vertex 5\n${xyz3}end_header\n0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n"
  "0.000000 1.000000 0.000000\n0.000000 0.000000 1.000000\n")
file(WRITE ${WORK}/more.ply "${ply_header}element vertex 4\n${xyz3}end_header\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n")
file(WRITE ${WORK}/word.ply "${ply_header}element vertex 4\n${xyz3}end_header\n0 0 0\n1 zero 0\n0 1 0\n0 0 1\n")
file(WRITE ${WORK}/word.xyz "0 0 0\n1 0 0\n0 1 0.5e\n0 0 1\n")
file(WRITE ${WORK}/two_numbers.xyz "0 0 0\n1 0 0\n# a comment\n0 1\n0 0 1\n")
file(WRITE ${WORK}/int64.ply "${ply_header}element vertex 1\nproperty int64 x\nproperty float y\nproperty float z\nend_header\n1 2 3\n")
file(WRITE ${WORK}/no_y.ply "${ply_header}element vertex 1\nproperty float x\nproperty float z\nend_header\n1 2\n")
file(WRITE ${WORK}/huge_binary.ply
  "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\n${xyz3}end_header\n0123456789ab")
file(WRITE ${WORK}/huge_ascii.ply "${ply_header}element vertex 4000000000\n${xyz3}end_header\n1 2 3\n")
file(MAKE_DIRECTORY ${WORK}/directory.ply)
# The bunny (binary little-endian) cut short, and the end of its body (binary floats) as text.
# CMake strings cannot hold a NUL byte, so head and tail cut the bytes.
execute_process(COMMAND head -c 100000 ${DATA} OUTPUT_FILE ${WORK}/truncated.ply)
execute_process(COMMAND tail -c 8000 ${DATA} OUTPUT_FILE ${WORK}/binary.xyz)
file(SIZE ${WORK}/truncated.ply size_a)
file(SIZE ${WORK}/binary.xyz size_b)
if(NOT size_a EQUAL 100000 OR NOT size_b EQUAL 8000)
  fail("could not cut the bunny: ${size_a} and ${size_b} bytes")
endif()

bad_file(empty.ply "empty file")
bad_file(header_only.ply "header only")
bad_file(no_end_header.ply "missing end_header")
bad_file(format.ply "line 2: unknown PLY format 'binary_middle_endian'")
bad_file(version.ply "line 2: unsupported PLY version '2.0'")
bad_file(points.dat "unknown file format")
bad_file(truncated.ply "byte offset [0-9]+: truncated binary body")
bad_file(fewer.ply "ends after 4 of 5 'vertex' records \\(line 11\\)")
bad_file(more.ply "line 12: more data than the header declares")
bad_file(word.ply "line 9: 'zero' is not a number")
bad_file(word.xyz "line 3: '0.5e' is not a number")
bad_file(two_numbers.xyz "line 4: expected 3 numbers \\(x y z\\), found 2")
bad_file(binary.xyz "line 1: binary data, not text")
bad_file(int64.ply "line 4: unknown property type 'int64'")
bad_file(no_y.ply "no 'y' property")
bad_file(directory.ply "is a directory")
bad_file(empty.ply/x "cannot open")
bad_file(missing.ply "no such file")

# A header declaring 4 billion vertices in a tiny file fails at once, without allocating on the
# header's word: under a 512 MiB address-space limit where the shell and the tool allow one (not
# under AddressSanitizer, which reserves terabytes of address space), and within 5 s.
execute_process(COMMAND sh -c "ulimit -v 524288 && exec \"$0\" --help" ${NMESH}
  RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
set(limit "")
if(rc EQUAL 0)
  set(limit "ulimit -v 524288 && ")
else()
  message("huge headers: no address-space limit here (sanitizer build); checking the time only")
endif()
foreach(name huge_binary.ply huge_ascii.ply)
  string(TIMESTAMP t0 "%s")
  expect(${name}_limited 1 "^nmesh: error: [^\n]*${name}: [^\n]*4000000000 'vertex', needing at least[^\n]*\n$"
    sh -c "${limit}exec \"$0\" reconstruct \"$1\" -o \"$2\" --quiet" ${NMESH} ${WORK}/${name} ${WORK}/out.ply)
  expect(${name}_info_limited 1 "4000000000 'vertex'" sh -c "${limit}exec \"$0\" info \"$1\"" ${NMESH} ${WORK}/${name})
  string(TIMESTAMP t1 "%s")
  math(EXPR dt "${t1} - ${t0}")
  check(${name}_fast "took ${dt} s" dt LESS 5)
endforeach()

# An ASCII PLY with a list property before x, y, z reads right.
file(WRITE ${WORK}/list_first.ply
  "${ply_header}element vertex 4\nproperty list uchar int tags\n${xyz3}property uchar red\nend_header\n"
  "2 7 8 0 0 0 255\n0 1 0 0 1\n3 1 2 3 0 1 0 2\n1 9 0 0 2 3\n")
expect(list_first_info 0 "points: 4\nfaces: 0\nbounding box: \\[0, 0, 0\\] to \\[1, 1, 2\\]" ${NMESH} info ${WORK}/list_first.ply)
expect(list_first_reconstruct 0 "read [^\n]*list_first.ply: 4 points.*wrote [^\n]*: 4 vertices, 4 faces"
  ${NMESH} reconstruct ${WORK}/list_first.ply -o ${WORK}/list_first_mesh.ply --vertices 4)

# Unreadable by permission: only meaningful when not root.
execute_process(COMMAND id -u OUTPUT_VARIABLE uid OUTPUT_STRIP_TRAILING_WHITESPACE)
if(uid STREQUAL "0")
  message("permission check skipped: running as root, which reads any file")
else()
  file(WRITE ${WORK}/secret.xyz "0 0 0\n")
  execute_process(COMMAND chmod 000 ${WORK}/secret.xyz)
  bad_file(secret.xyz "cannot open: [Pp]ermission denied")
  execute_process(COMMAND chmod 644 ${WORK}/secret.xyz)
endif()

# Outputs: a missing directory, and the input itself under other spellings of its path.
# Unwritable outputs are found before the input is read (no "read" line), not after learning.
expect(output_missing_dir 1 "^nmesh: error: [^\n]*nodir/out.ply: cannot write: directory [^\n]* does not exist\n$"
  ${NMESH} reconstruct ${bunny} -o ${WORK}/nodir/out.ply --vertices 20000)
expect(stats_missing_dir 1 "^nmesh: error: [^\n]*nodir/stats.json: cannot write[^\n]*\n$"
  ${NMESH} reconstruct ${bunny} -o ${WORK}/with_stats.ply --stats ${WORK}/nodir/stats.json --vertices 20000)
expect(output_unknown_format 1 "^nmesh: error: [^\n]*out.stl: unknown mesh format '.stl'[^\n]*\n$"
  ${NMESH} reconstruct ${bunny} -o ${WORK}/out.stl --vertices 20000)
file(MAKE_DIRECTORY ${WORK}/clash.ply)
expect(output_is_directory 1 "^nmesh: error: [^\n]*clash.ply: cannot write: is a directory\n$"
  ${NMESH} reconstruct ${bunny} -o ${WORK}/clash.ply --vertices 20000)
file(REMOVE_RECURSE ${WORK}/clash.ply)
check(unwritable_outputs_nothing_written "a refused run left with_stats.ply or out.stl"
  NOT EXISTS ${WORK}/with_stats.ply AND NOT EXISTS ${WORK}/out.stl)
file(SHA256 ${bunny} copy_sha)
# Known defect: the tool compares the output and input paths as strings, so the same file named
# with a "./" prefix or an absolute path is not refused, and the mesh replaces the input.
expect(output_is_input_plain 2 "must not be the input" ${NMESH} reconstruct ${bunny} -o ${bunny} --quiet)
expect(output_is_input_dot 2 "must not be the input"
  ${CMAKE_COMMAND} -E chdir ${WORK} ${NMESH} reconstruct ${data_name} -o ./${data_name} --vertices 50 --quiet)
file(COPY ${DATA} DESTINATION ${WORK})  # restore the copy if it was replaced
expect(output_is_input_absolute 2 "must not be the input"
  ${CMAKE_COMMAND} -E chdir ${WORK} ${NMESH} reconstruct ${data_name} -o ${bunny} --vertices 50 --quiet)
file(COPY ${DATA} DESTINATION ${WORK})
# --stats and the snapshot names must not name the input, nor --stats the mesh: a usage error,
# the input untouched.
file(MAKE_DIRECTORY ${WORK}/clash)
foreach(case "stats_is_input;in.ply;--stats;in.ply" "snapshot_is_input;mesh_100v.ply;--snapshots;100"
    "stats_is_output;in.ply;--stats;mesh.ply")
  list(GET case 0 name)
  list(GET case 1 input)
  list(GET case 2 option)
  list(GET case 3 value)
  configure_file(${DATA} ${WORK}/clash/${input} COPYONLY)
  execute_process(COMMAND ${NMESH} reconstruct ${input} -o mesh.ply ${option} ${value} --vertices 200 --quiet
    WORKING_DIRECTORY ${WORK}/clash RESULT_VARIABLE rc OUTPUT_QUIET ERROR_QUIET)
  file(SHA256 ${WORK}/clash/${input} input_sha)
  set(mesh_ok FALSE)
  if(EXISTS ${WORK}/clash/mesh.ply)
    file(READ ${WORK}/clash/mesh.ply mesh_head LIMIT 3)
    if(mesh_head STREQUAL "ply")
      set(mesh_ok TRUE)
    endif()
  endif()
  if(name STREQUAL "stats_is_output")
    check(${name} "exit status ${rc}; mesh.ply does not hold the mesh" rc EQUAL 2 OR mesh_ok)
  else()
    check(${name} "exit status ${rc}; ${input} was replaced" input_sha STREQUAL data_sha_before)
  endif()
  file(REMOVE_RECURSE ${WORK}/clash)
  file(MAKE_DIRECTORY ${WORK}/clash)
endforeach()
# A device is not a regular file: refused, not read (a pipe would otherwise block).
expect(not_regular_file 1 "^nmesh: error: /dev/null: not a regular file\n$" ${NMESH} info /dev/null)

# ---- 2. Degenerate clouds and parameters -----------------------------------------------------
# A cloud as OBJ "v" lines: the vertices of a small reconstruction of the bunny.
expect(make_cloud 0 "" ${NMESH} reconstruct ${bunny} -o ${WORK}/cloud.obj --vertices 400 --quiet)
file(READ ${WORK}/cloud.obj cloud)
string(REGEX REPLACE "f [^\n]*\n" "" cloud "${cloud}")
file(WRITE ${WORK}/nan.obj "${cloud}v nan 0 0\nv 1 inf 2\nv 0 0 -infinity\n")
expect(nan_dropped 0 "read [^\n]*nan.obj: 400 points[^\n]*\nnmesh: warning: [^\n]*nan.obj: dropped 3 points with NaN or infinite coordinates\n"
  ${NMESH} reconstruct ${WORK}/nan.obj -o ${WORK}/nan_mesh.ply --vertices 100)
# --quiet silences progress and the summary, not warnings.
expect(nan_dropped_quiet 0 "^nmesh: warning: [^\n]*nan.obj: dropped 3 points with NaN or infinite coordinates\n$"
  ${NMESH} reconstruct ${WORK}/nan.obj -o ${WORK}/nan_mesh.ply --vertices 100 --quiet)
expect(nan_info 0 "points: 400\npoints with NaN or infinite coordinates: 3" ${NMESH} info ${WORK}/nan.obj)
file(WRITE ${WORK}/all_nan.xyz "nan 0 0\n0 inf 0\n")
expect(all_nan 1 "all_nan.xyz: 0 points[^\n]*\nnmesh: warning: [^\n]*all_nan.xyz: dropped 2 points[^\n]*\nnmesh: error: [^\n]*all_nan.xyz: [^\n]*0 points[^\n]*\n$"
  ${NMESH} reconstruct ${WORK}/all_nan.xyz -o ${WORK}/out.ply --vertices 10)
file(WRITE ${WORK}/duplicates.obj "${cloud}${cloud}${cloud}")
expect(duplicates 0 "wrote [^\n]*: 300 vertices, 596 faces"
  ${NMESH} reconstruct ${WORK}/duplicates.obj -o ${WORK}/duplicates_mesh.ply --vertices 300)
file(WRITE ${WORK}/three.xyz "0 0 0\n1 0 0\n0 1 0\n1 0 0\n0 0 0\n")
expect(three_distinct 1 "^nmesh: error: [^\n]*three.xyz: [^\n]*only 3 distinct points[^\n]*\n$"
  ${NMESH} reconstruct ${WORK}/three.xyz -o ${WORK}/out.ply --vertices 10 --quiet)
file(WRITE ${WORK}/identical.xyz "1 2 3\n1 2 3\n1 2 3\n1 2 3\n1 2 3\n")
expect(identical 1 "^nmesh: error: [^\n]*identical.xyz: [^\n]*identical[^\n]*\n$"
  ${NMESH} reconstruct ${WORK}/identical.xyz -o ${WORK}/out.ply --vertices 10 --quiet)
set(line "")
set(plane "")
foreach(i RANGE 0 19)
  math(EXPR y "2 * ${i}")
  math(EXPR z "3 * ${i} + 1")
  string(APPEND line "${i} ${y} ${z}\n")
  foreach(j RANGE 0 19)
    math(EXPR w "${i} + 2 * ${j}")
    string(APPEND plane "${i} ${j} ${w}\n")
  endforeach()
endforeach()
file(WRITE ${WORK}/line.xyz "${line}")
expect(collinear 1 "^nmesh: error: [^\n]*line.xyz: [^\n]*one line[^\n]*\n$"
  ${NMESH} reconstruct ${WORK}/line.xyz -o ${WORK}/out.ply --vertices 10 --quiet)
file(WRITE ${WORK}/plane.xyz "${plane}")
expect(coplanar 0 "wrote [^\n]*: 200 vertices, 396 faces"
  ${NMESH} reconstruct ${WORK}/plane.xyz -o ${WORK}/plane_mesh.ply --vertices 200)
expect(coplanar_closed 0 "\"closed\": true.*\"manifold\": true.*\"genus\": 0" ${NMESH} eval ${WORK}/plane.xyz ${WORK}/plane_mesh.ply --json)
if(EXISTS ${WORK}/out.ply)
  fail("a refused cloud left out.ply behind")
endif()
# With fewer points than about 1/1.3 of the target the mesh stops growing below the target: the
# run stops with an error saying so (here 4 points and the default 10,000 vertices), within 5 s,
# and writes nothing.
file(WRITE ${WORK}/four.xyz "0 0 0\n1 0 0\n0 1 0\n0 0 1\n")
execute_process(COMMAND ${NMESH} reconstruct ${WORK}/four.xyz -o ${WORK}/four_mesh.ply --quiet
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 5)
check(four_points_default_target "exit status '${rc}' (5 s limit)\n${out}${err}"
  rc EQUAL 1 AND err MATCHES "^nmesh: error: [^\n]*four.xyz: the mesh stopped growing at [0-9]+ vertices[^\n]*4 points cannot carry 10000 vertices[^\n]*\n$")
check(four_points_nothing_written "a refused run left four_mesh.ply" NOT EXISTS ${WORK}/four_mesh.ply)
# The --stats JSON holds the input's name as a valid JSON string whatever its characters.
set(odd_name "we\"ird\\name\tx.xyz")
file(WRITE "${WORK}/${odd_name}" "${plane}")
expect(stats_odd_input_name 0 "" ${NMESH} reconstruct "${WORK}/${odd_name}" -o ${WORK}/odd.ply
  --stats ${WORK}/odd.json --vertices 50 --quiet)
file(READ ${WORK}/odd.json odd_json)
string(JSON odd_input ERROR_VARIABLE odd_error GET "${odd_json}" input)
check(stats_odd_input_json "input read back from the JSON: '${odd_input}' (${odd_error})"
  odd_input STREQUAL "${WORK}/${odd_name}")
# A target of 4 is the tetrahedron, fitted to the cloud: its vertices move from where they start.
expect(four_vertices 0 "wrote [^\n]*: 4 vertices, 4 faces\nnmesh: ([1-9][0-9]*) iterations"
  ${NMESH} reconstruct ${bunny} -o ${WORK}/tetra.ply --vertices 4)

# Invalid parameters: a usage error (status 2), one line naming the option or parameter.
# Every option is checked before the input is read.
foreach(bad
    "--alpha-w;0;invalid parameter alpha_w" "--alpha-w;1.01;invalid parameter alpha_w"
    "--alpha-w;nan;--alpha-w needs a number" "--alpha;inf;--alpha needs a number"
    "--alpha-n;-0.5;invalid parameter alpha_n" "--cec;0;invalid parameter cec"
    "--settle;-1;invalid parameter settle" "--vertices;-5;--vertices needs a whole number"
    "--vertices;5000000000;--vertices is too large" "--vertices;1e4;--vertices needs a whole number"
    "--seed;x;--seed needs a whole number" "--snapshots;10,,20;--snapshots needs a whole number"
    "--cvs;99999999999;--cvs is too large" "--finish-rounds;1001;invalid parameter finish_rounds"
    "--finish-rounds;-1;--finish-rounds needs a whole number" "--fit-rounds;101;invalid parameter fit_rounds"
    "--fit-rounds;-1;--fit-rounds needs a whole number"
    "--surface-fit-rounds;101;invalid parameter surface_fit_rounds"
    "--surface-fit-rounds;-1;--surface-fit-rounds needs a whole number"
    "--exchange-passes;101;invalid parameter exchange_passes")
  list(GET bad 0 option)
  list(GET bad 1 value)
  list(GET bad 2 regex)
  expect(parameter_${option}_${value} 2 "^nmesh: [^\n]*${regex}[^\n]*\n$"
    ${NMESH} reconstruct ${bunny} -o ${WORK}/out.ply ${option} ${value})
endforeach()
# The centroid fit is part of the finishing stage: asking for it without the stage is refused.
expect(fit_without_finish 2 "^nmesh: [^\n]*fit_rounds: needs the finishing stage[^\n]*\n$"
  ${NMESH} reconstruct ${bunny} -o ${WORK}/out.ply --fit-rounds 1 --no-finish)

# ---- 3. Interrupted runs ---------------------------------------------------------------------
# interrupt.sh SIGNAL OUTPUT [OPTION...]: starts a reconstruction of the bunny large enough to
# take several seconds, waits until it has read its input, sends SIGNAL a second later and prints
# the exit status.
file(WRITE ${WORK}/interrupt.sh [=[
nmesh=$1 input=$2 signal=$3 output=$4 log=$5
shift 5
"$nmesh" reconstruct "$input" -o "$output" --vertices 44000 "$@" 2> "$log" &
pid=$!
i=0
while ! grep -q "read" "$log" 2> /dev/null && [ $i -lt 300 ]; do sleep 0.1; i=$((i + 1)); done
sleep 1
kill -s "$signal" $pid
wait $pid
echo "status $?"
]=])
file(MAKE_DIRECTORY ${WORK}/interrupted)
foreach(signal INT TERM)
  foreach(save "" --save-on-interrupt)
    set(name interrupt_${signal}${save})
    set(out ${WORK}/interrupted/${signal}${save}.ply)
    set(log ${WORK}/interrupted/${signal}${save}.log)
    execute_process(COMMAND sh ${WORK}/interrupt.sh ${NMESH} ${bunny} ${signal} ${out} ${log} ${save}
      OUTPUT_VARIABLE status TIMEOUT 120)
    set(log_text "")
    if(EXISTS ${log})
      file(READ ${log} log_text)
    endif()
    set(expected_status "status 130\n")
    check(${name}_status "${status}${log_text}" status STREQUAL expected_status)
    file(GLOB temps ${WORK}/interrupted/*.tmp-*)
    check(${name}_no_temporary "left ${temps}" NOT temps)
    if(save STREQUAL "")
      check(${name}_nothing_written "wrote ${out}" NOT EXISTS ${out})
      check(${name}_says_so "${log_text}" log_text MATCHES "interrupted after [0-9]+ iterations. nothing written")
    else()
      execute_process(COMMAND ${NMESH} info ${out} OUTPUT_VARIABLE info RESULT_VARIABLE rc)
      if(rc EQUAL 0 AND info MATCHES "points: ([0-9]+)\nfaces: ([0-9]+)")
        set(v ${CMAKE_MATCH_1})
        set(f ${CMAKE_MATCH_2})
        math(EXPR expected_f "2 * ${v} - 4")
        check(${name}_valid_mesh "${v} vertices, ${f} faces" f EQUAL expected_f AND v LESS 44000 AND v GREATER 3)
      else()
        verdict(${name}_valid_mesh FALSE "nmesh info ${out}: status ${rc}\n${info}")
      endif()
      check(${name}_says_so "${log_text}" log_text MATCHES "interrupted. wrote the mesh reached so far")
    endif()
  endforeach()
endforeach()

# ---- The inputs are never modified -----------------------------------------------------------
file(SHA256 ${DATA} data_sha_after)
file(SHA256 ${bunny} copy_sha_after)
check(data_unchanged "${DATA} changed" data_sha_after STREQUAL data_sha_before)
check(copy_unchanged "${bunny} changed" copy_sha_after STREQUAL data_sha_before)

message("cli_robustness: ${passes} passed, ${failures} failed, ${known} known defects")
if(failures GREATER 0)
  message(FATAL_ERROR "${failures} CLI robustness checks failed")
endif()
