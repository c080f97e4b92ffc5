# Runs the dbss command on good, damaged and missing files and checks exit
# codes and messages.  Invoked by CTest with -DDBSS, -DEXAMPLE, -DMESH_HASH,
# -DGLTF_LODS, -DWORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})

function(expect_run expected_rc must_contain)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expected_rc)
    message(FATAL_ERROR "'${ARGN}' exited ${rc}, expected ${expected_rc}\nstdout: ${out}\nstderr: ${err}")
  endif()
  if(must_contain AND NOT "${out}${err}" MATCHES "${must_contain}")
    message(FATAL_ERROR "'${ARGN}' output lacks '${must_contain}'\nstdout: ${out}\nstderr: ${err}")
  endif()
endfunction()

set(f ${WORK}/torus.dbss)
expect_run(0 "level 3: 3200 vertices \\(2400 odd\\), 6400 triangles" ${EXAMPLE} ${f})
expect_run(0 "complete, every chunk verified" ${DBSS} info ${f})
expect_run(0 "\"complete\": true" ${DBSS} info ${f} --json)
expect_run(0 "usage: dbss info" ${DBSS} info --help)
expect_run(0 "commands:" ${DBSS} --help)
expect_run(1 "usage: dbss" ${DBSS})
expect_run(1 "unknown command 'frobnicate'" ${DBSS} frobnicate)
expect_run(1 "unknown option '--bogus'" ${DBSS} info ${f} --bogus)
expect_run(1 "${WORK}/missing.dbss: cannot open" ${DBSS} info ${WORK}/missing.dbss)
expect_run(1 "is a directory" ${DBSS} info ${WORK})

# A cut file: verified chunks are listed, the error names the truncation.
# A cut file: verified chunks are listed, the error names the truncation.
file(SIZE ${f} n)
find_program(HEAD head)
if(HEAD)
  math(EXPR bytes "${n} / 2")
  execute_process(COMMAND ${HEAD} -c ${bytes} ${f} OUTPUT_FILE ${WORK}/cut.dbss)
  expect_run(1 "truncated at byte" ${DBSS} info ${WORK}/cut.dbss)
  execute_process(COMMAND ${HEAD} -c 100 ${f} OUTPUT_FILE ${WORK}/cut2.dbss)
  expect_run(1 "NOT complete" ${DBSS} info ${WORK}/cut2.dbss)
endif()
# encode and decode.
set(example ${SOURCE}/examples/double-torus.xyz)
set(g ${WORK}/dt.dbss)
expect_run(0 "genus 2" ${DBSS} encode ${example} -o ${g} --dump-stages ${WORK}/stages)
foreach(stage 1-occupied-cells 2-carved-cells 3-triangulated 4-shrink-wrapped 5-simplified 6-control)
  if(NOT EXISTS ${WORK}/stages/${stage}.obj)
    message(FATAL_ERROR "--dump-stages did not write ${stage}.obj")
  endif()
endforeach()
expect_run(0 "complete, every chunk verified" ${DBSS} info ${g})
# info names each level's coding; a golden file of format 1.2 (section 9b).
expect_run(0 "format 1\\.2, 3 levels.*\n1 .* context " ${DBSS} info ${SOURCE}/tests/golden/v1/bipyramid9-context-3-levels.dbss)
# The default is --levels auto: the example's 8000 points stop it at level 3
# (2462 vertices at level 2, 9854 at level 3); the decoded finest level is 3.
expect_run(0 "3 level\\(s\\) \\(auto: level 3 is the first with more vertices than the [0-9]+ points\\)"
           ${DBSS} encode ${example} -o ${WORK}/auto.dbss --levels auto)
expect_run(0 "level 3, [0-9]+ vertices" ${DBSS} decode ${g} -o ${WORK}/dt.off)
file(STRINGS ${WORK}/dt.off off_header LIMIT_COUNT 2)
if(NOT off_header MATCHES "OFF;[0-9]+ [0-9]+ 0")
  message(FATAL_ERROR "decode wrote a bad OFF header: ${off_header}")
endif()
expect_run(0 "level 0" ${DBSS} decode ${g} -o ${WORK}/dt.ply --level 0)
expect_run(1 "level 4 is not in the file" ${DBSS} decode ${g} -o ${WORK}/x.ply --level 4)
expect_run(1 "--levels needs auto or a whole number" ${DBSS} encode ${example} -o ${WORK}/x.dbss --levels 9)
expect_run(1 "--error needs a number" ${DBSS} encode ${example} -o ${WORK}/x.dbss --error abc)
expect_run(1 "unknown mesh format" ${DBSS} decode ${g} -o ${WORK}/x.vrml)
# Encode -> decode through every supported input format: the decoded level
# written in each format is read back as points and encoded again.
foreach(ext ply obj off stl glb gltf)
  expect_run(0 "-> ${WORK}/rt.${ext}" ${DBSS} decode ${g} -o ${WORK}/rt.${ext})
  expect_run(0 "genus 2" ${DBSS} encode ${WORK}/rt.${ext} -o ${WORK}/rt-${ext}.dbss --levels 1)
  expect_run(0 "complete, every chunk verified" ${DBSS} info ${WORK}/rt-${ext}.dbss)
endforeach()
# Mesh input: a file with faces is encoded as a mesh (the loop above), its
# topology reported and kept at every level; --input points reconstructs
# from its vertices instead; non-manifold meshes are refused by name.
expect_run(0 "input: 1 component\\(s\\), genus 2, 0 boundary loop\\(s\\)" ${DBSS} encode ${WORK}/rt.off -o ${WORK}/mesh.dbss --levels 2)
expect_run(0 "\n2 +[0-9]+ +[0-9]+ +[0-9]+ +1 +2 +0 " ${DBSS} encode ${WORK}/rt.off -o ${WORK}/mesh.dbss --levels 2)
expect_run(0 "self-check: " ${DBSS} encode ${WORK}/rt.off -o ${WORK}/points.dbss --levels 1 --input points)
# --no-report: the levels' distances are not measured ("-" where the report
# has a figure; the sizes stay, on both paths), and the file is the same
# byte for byte.
expect_run(0 "\n2 +[0-9]+ +[0-9]+ +[0-9]+ +1 +2 +0 +[0-9.]+e-[0-9]+\n" ${DBSS} encode ${WORK}/rt.off -o ${WORK}/mesh.dbss --levels 2)
expect_run(0 "\n2 +[0-9]+ +[0-9]+ +[0-9]+ +1 +2 +0 +-\n.*--no-report" ${DBSS} encode ${WORK}/rt.off -o ${WORK}/mesh-nr.dbss --levels 2 --no-report)
execute_process(COMMAND ${DBSS} encode ${WORK}/rt.off -o ${WORK}/points-nr.dbss --levels 1 --input points --no-report
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out MATCHES "\n1 +[0-9]+ +[0-9]+ [^\n]* +- +-\n" OR NOT out MATCHES "self-check: ")
  message(FATAL_ERROR "--no-report on points: exit ${rc}, expected level 1's sizes with '-' for its distances, and the self-check\nstdout: ${out}\nstderr: ${err}")
endif()
foreach(kind mesh points)
  file(SHA256 ${WORK}/${kind}.dbss with_report)
  file(SHA256 ${WORK}/${kind}-nr.dbss without_report)
  if(NOT with_report STREQUAL without_report)
    message(FATAL_ERROR "--no-report changed the ${kind} file")
  endif()
endforeach()
# --input points is the point path exactly: the same surface as the mesh's
# vertices alone in an .xyz file (OFF vertex lines are "x y z" as in XYZ).
file(STRINGS ${WORK}/rt.off rt_lines)
list(GET rt_lines 1 rt_counts)
string(REGEX MATCH "^[0-9]+" rt_vertices "${rt_counts}")
list(SUBLIST rt_lines 2 ${rt_vertices} rt_points)
list(JOIN rt_points "\n" rt_points)
file(WRITE ${WORK}/rt-points.xyz "${rt_points}\n")
expect_run(0 "self-check: " ${DBSS} encode ${WORK}/rt-points.xyz -o ${WORK}/points-xyz.dbss --levels 1)
expect_run(0 "-> " ${DBSS} decode ${WORK}/points.dbss -o ${WORK}/points-off.off)
expect_run(0 "-> " ${DBSS} decode ${WORK}/points-xyz.dbss -o ${WORK}/points-xyz.off)
file(READ ${WORK}/points-off.off from_off)
file(READ ${WORK}/points-xyz.off from_xyz)
if(NOT from_off STREQUAL from_xyz)
  message(FATAL_ERROR "--input points on rt.off and its vertices as rt-points.xyz decode differently")
endif()
expect_run(1 "--input needs points or mesh" ${DBSS} encode ${WORK}/rt.off -o ${WORK}/x.dbss --input faces)
expect_run(1 "double-torus.xyz: --input mesh, but the file has no faces" ${DBSS} encode ${example} -o ${WORK}/x.dbss --input mesh)
file(WRITE ${WORK}/fin.off "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n")
expect_run(1 "fin.off: edge 0-1 is shared by 3 triangles \\(non-manifold\\)" ${DBSS} encode ${WORK}/fin.off -o ${WORK}/fin.dbss)
file(WRITE ${WORK}/bowtie.off "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n")
expect_run(1 "bowtie.off: vertex 0 joins 2 triangles in more than one fan" ${DBSS} encode ${WORK}/bowtie.off -o ${WORK}/fin.dbss)
# Two triangles back to back: closed and manifold, but no surface; bad
# input (exit 1), not an encoder failure (exit 2).
file(WRITE ${WORK}/pillow.off "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n")
expect_run(1 "pillow.off: the control mesh lost the input's topology" ${DBSS} encode ${WORK}/pillow.off -o ${WORK}/fin.dbss)
if(EXISTS ${WORK}/fin.dbss)
  message(FATAL_ERROR "a refused mesh left ${WORK}/fin.dbss behind")
endif()
expect_run(0 "-> " ${DBSS} encode ${example} -o ${WORK}/step.dbss --levels 1 --step 0.001)
expect_run(0 "0.001 " ${DBSS} info ${WORK}/step.dbss)
expect_run(0 "usage: dbss encode" ${DBSS} encode --help)
expect_run(0 "usage: dbss decode" ${DBSS} decode --help)
expect_run(1 "no output file" ${DBSS} encode ${example})
expect_run(1 "--grid needs a whole number" ${DBSS} encode ${example} -o ${WORK}/x.dbss --grid 1)
expect_run(1 "--control-faces needs an even" ${DBSS} encode ${example} -o ${WORK}/x.dbss --control-faces 7)
expect_run(1 "missing.xyz: cannot open" ${DBSS} encode ${WORK}/missing.xyz -o ${WORK}/x.dbss)
file(WRITE ${WORK}/flat.xyz "0 0 0\n1 0 0\n0 1 0\n1 1 0\n2 3 0\n")
expect_run(1 "flat.xyz: all points lie on one plane" ${DBSS} encode ${WORK}/flat.xyz -o ${WORK}/x.dbss)
file(WRITE ${WORK}/bad.xyz "0 0 0\n1 2\n")
expect_run(1 "bad.xyz: line 2" ${DBSS} encode ${WORK}/bad.xyz -o ${WORK}/x.dbss)
# Hostile inputs: tests/hostile_input_test.cmake, one CTest entry each.
if(EXISTS ${WORK}/x.dbss)
  message(FATAL_ERROR "a failed encode left an output file behind")
endif()

file(WRITE ${WORK}/text.dbss "hello, this is not a dbss file\n")
expect_run(1 "bad_signature" ${DBSS} info ${WORK}/text.dbss)

# compare: dbss against the full-vertex DSS and Draco, per level.
expect_run(0 "usage: dbss compare" ${DBSS} compare --help)
expect_run(1 "no input file" ${DBSS} compare)
expect_run(1 "unknown option '--bogus'" ${DBSS} compare ${example} --bogus)
expect_run(1 "--levels needs auto or a whole number" ${DBSS} compare ${example} --levels x)
expect_run(1 "missing.xyz: cannot open" ${DBSS} compare ${WORK}/missing.xyz)
expect_run(0 "DSS all B" ${DBSS} compare ${example} --levels 2)
expect_run(0 "\"dss_all_bytes\": [0-9]+, \"dbss_clamped\"" ${DBSS} compare ${example} --levels 1 --json --no-errors)

# A failed encode leaves an existing output as it was.
file(WRITE ${WORK}/keep.dbss "the old output")
expect_run(1 "bad.xyz: line 2" ${DBSS} encode ${WORK}/bad.xyz -o ${WORK}/keep.dbss)
file(READ ${WORK}/keep.dbss kept)
if(NOT kept STREQUAL "the old output")
  message(FATAL_ERROR "a failed encode changed the existing output")
endif()
# A --dump-stages directory that cannot be made fails before any output.
file(WRITE ${WORK}/not-a-dir "")
file(REMOVE ${WORK}/dumped.dbss)
expect_run(1 "cannot create directory" ${DBSS} encode ${example} -o ${WORK}/dumped.dbss --dump-stages ${WORK}/not-a-dir/stages)
if(EXISTS ${WORK}/dumped.dbss)
  message(FATAL_ERROR "a failed --dump-stages left an output behind")
endif()
# --effort and --control-bits reach the file, and it still decodes.
expect_run(0 "-> " ${DBSS} encode ${example} -o ${WORK}/e1.dbss --levels 1 --effort 1 --control-bits 12)
expect_run(0 "complete, every chunk verified" ${DBSS} info ${WORK}/e1.dbss)
expect_run(0 "12-bit positions" ${DBSS} info ${WORK}/e1.dbss)
expect_run(0 "level 1" ${DBSS} decode ${WORK}/e1.dbss -o ${WORK}/e1.ply)

# Progress goes only to a terminal: with stderr redirected, a run longer
# than the one second after which progress would show (3.5 s here, progress
# calls after the first second) prints nothing there.
execute_process(COMMAND ${DBSS} compare ${example} --levels 5 RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT err STREQUAL "")
  message(FATAL_ERROR "compare with stderr redirected: exit ${rc}, stderr '${err}'")
endif()

# Real-scan handling.  The example's upper half (z >= 0) is an open patch of
# a genus-2 surface: `auto` keeps it open with its three boundary loops (the
# rim and the two holes) and says so, also in the file's meta chunk.
file(STRINGS ${example} lines REGEX "^[^#]")
set(upper "")
set(stray "")
foreach(line IN LISTS lines)
  if(line MATCHES "^[^ ]+ [^ ]+ [0-9]")
    string(APPEND upper "${line}\n")
  endif()
endforeach()
file(WRITE ${WORK}/upper.xyz "${upper}")
expect_run(0 "surface +[0-9.]+ +- +- +open: " ${DBSS} encode ${WORK}/upper.xyz -o ${WORK}/upper.dbss --levels 1)
expect_run(0 "self-check: ok: 1 component\\(s\\) for 1 point cluster\\(s\\), open, 3 boundary loop\\(s\\)" ${DBSS} encode ${WORK}/upper.xyz -o ${WORK}/upper.dbss --levels 1)
expect_run(0 "surface = open: " ${DBSS} info ${WORK}/upper.dbss)
expect_run(0 "level 1" ${DBSS} decode ${WORK}/upper.dbss -o ${WORK}/upper.ply)
# Asked to close it, the holes are bridged: one closed surface of genus 2.
expect_run(0 "self-check: [^\n]*1 component\\(s\\) for 1 point cluster\\(s\\), closed" ${DBSS} encode ${WORK}/upper.xyz -o ${WORK}/upper-closed.dbss --levels 1 --surface closed)
expect_run(0 "unsupported.bridged_area_share = 0\\.[0-9]+" ${DBSS} info ${WORK}/upper-closed.dbss)
expect_run(1 "--surface needs closed, open or auto" ${DBSS} encode ${WORK}/upper.xyz -o ${WORK}/x.dbss --surface half)
# A dozen stray points around the example: dropped by default, and the
# result is the clean one.
foreach(i RANGE 1 12)
  math(EXPR x "${i} % 5 - 2")
  math(EXPR y "${i} % 3 - 1")
  math(EXPR z "${i} % 2")
  string(APPEND stray "${x}.5 ${y}.7 ${z}.9\n")
endforeach()
file(READ ${example} clean)
file(WRITE ${WORK}/stray.xyz "${clean}${stray}")
# The clean example's own count (points the off-plane test takes: a few
# where its two tori meet), plus the dozen; and the same levels as the
# clean example's, bit for bit.
execute_process(COMMAND ${DBSS} encode ${example} -o ${WORK}/clean.dbss --levels 1 OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT "${out}" MATCHES " ([0-9]+) isolated points dropped")
  message(FATAL_ERROR "encode of the example printed no outlier count\nstdout: ${out}\nstderr: ${err}")
endif()
math(EXPR with_strays "${CMAKE_MATCH_1} + 12")
expect_run(0 " ${with_strays} isolated points dropped" ${DBSS} encode ${WORK}/stray.xyz -o ${WORK}/stray.dbss --levels 1)
expect_run(0 "self-check: ok: 1 component\\(s\\)" ${DBSS} encode ${WORK}/stray.xyz -o ${WORK}/stray.dbss --levels 1 --strict)
expect_run(0 "outliers = 0 duplicates, ${with_strays} isolated points" ${DBSS} info ${WORK}/stray.dbss)
foreach(name clean stray)
  execute_process(COMMAND ${DBSS} info ${WORK}/${name}.dbss --hashes OUTPUT_VARIABLE info_${name})
  string(REGEX MATCHALL "level [0-9]+ vertices [0-9]+ triangles [0-9]+ fnv1a64 [0-9a-f]+" hashes_${name} "${info_${name}}")
endforeach()
if(NOT hashes_clean OR NOT hashes_clean STREQUAL hashes_stray)
  message(FATAL_ERROR "the example with strays decodes unlike the clean one:\n${hashes_clean}\n${hashes_stray}")
endif()
# A carving grid far too coarse for the example: the self-check names what
# is wrong, the file records it, and --strict writes nothing.
expect_run(0 "warning \\(distance\\): the points lie [0-9.]+ point spacings" ${DBSS} encode ${example} -o ${WORK}/coarse.dbss --levels 1 --grid 6)
expect_run(0 "warning.distance = " ${DBSS} info ${WORK}/coarse.dbss)
file(REMOVE ${WORK}/strict.dbss)
expect_run(1 "warning\\(s\\) under --strict; [^\n]*strict.dbss not written" ${DBSS} encode ${example} -o ${WORK}/strict.dbss --levels 1 --grid 6 --strict)
if(EXISTS ${WORK}/strict.dbss)
  message(FATAL_ERROR "--strict with warnings left an output behind")
endif()

# `dbss info --hashes` (spec/decoding.md section 8): the test vector's lines
# must be exactly the ones the spec publishes, a golden file's hashes the
# recorded ones.
set(vector ${SOURCE}/spec/test-vector/open-bipyramid-2-levels.dbss)
file(READ ${SOURCE}/spec/decoding.md spec_md)
if(NOT spec_md MATCHES "```hashes\n([^`]*)```")
  message(FATAL_ERROR "spec/decoding.md has no ```hashes block")
endif()
set(published "${CMAKE_MATCH_1}")
execute_process(COMMAND ${DBSS} info --hashes ${vector} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT out STREQUAL published OR NOT err STREQUAL "")
  message(FATAL_ERROR "info --hashes on the test vector: exit ${rc}\n${out}expected:\n${published}stderr: ${err}")
endif()
set(golden ${SOURCE}/tests/golden/v1/torus-4-levels)
file(STRINGS ${golden}.hashes recorded)
execute_process(COMMAND ${DBSS} info --hashes ${golden}.dbss RESULT_VARIABLE rc OUTPUT_VARIABLE out)
string(REGEX REPLACE "\n$" "" out "${out}")
string(REPLACE "\n" ";" lines "${out}")
set(l 0)
foreach(line IN LISTS lines)
  list(GET recorded ${l} hash)
  if(NOT line MATCHES "^level ${l} vertices [0-9]+ triangles [0-9]+ fnv1a64 ${hash}$")
    message(FATAL_ERROR "info --hashes on ${golden}.dbss: '${line}', recorded hash ${hash}")
  endif()
  math(EXPR l "${l} + 1")
endforeach()
list(LENGTH recorded n_recorded)
if(NOT rc EQUAL 0 OR NOT l EQUAL n_recorded)
  message(FATAL_ERROR "info --hashes on ${golden}.dbss: exit ${rc}, ${l} lines for ${n_recorded} levels")
endif()
# --json carries the same hash: the published level 2 line's.
string(REGEX MATCH "level 2 [^\n]* fnv1a64 ([0-9a-f]+)" _ "${published}")
expect_run(0 "\"fnv1a64\": \"${CMAKE_MATCH_1}\"" ${DBSS} info ${vector} --json --hashes)
expect_run(0 "--hashes" ${DBSS} info --help)

# spec section 11: an error voids nothing verified before it.  Bytes after
# the file: decode still writes a verified level (warning, exit 0); info
# says the file is invalid and which levels are usable (exit 1).
configure_file(${vector} ${WORK}/trailing.dbss COPYONLY)
file(APPEND ${WORK}/trailing.dbss "x")
expect_run(0 "warning: .*trailing_data.*levels 0..2 were verified" ${DBSS} decode ${WORK}/trailing.dbss -o ${WORK}/t.ply --level 2)
expect_run(1 "levels 0..2 were verified before the error and are usable" ${DBSS} info ${WORK}/trailing.dbss)
if(HEAD)
  # Cut inside level 2: level 1 decodes, level 2 is not available.
  execute_process(COMMAND ${HEAD} -c 400 ${vector} OUTPUT_FILE ${WORK}/cut-vector.dbss)
  expect_run(0 "level 1, 22 vertices" ${DBSS} decode ${WORK}/cut-vector.dbss -o ${WORK}/c.ply --level 1)
  expect_run(1 "level 2 is not available: truncated" ${DBSS} decode ${WORK}/cut-vector.dbss -o ${WORK}/c.ply --level 2)
  expect_run(0 "level 1, 22 vertices" ${DBSS} decode ${WORK}/cut-vector.dbss -o ${WORK}/c.ply)
endif()

# A valid container whose control mesh is not Draco: info verifies it as
# decode does, so both fail.
set(garbage ${SOURCE}/tests/format/data/garbage-control.dbss)
expect_run(1 "compression: control mesh" ${DBSS} info ${garbage})
expect_run(1 "\"complete\": false" ${DBSS} info ${garbage} --json)
expect_run(1 "compression: control mesh" ${DBSS} decode ${garbage} -o ${WORK}/g.ply)

# `dbss decode` writes the decoded level itself: at every level of a golden
# file, the positions read back from the written PLY, OBJ, OFF, GLB and glTF
# hash to the level's recorded hash (binary32 survives PLY's and glTF's bytes
# and the 9 significant digits of OBJ and OFF exactly), with the level's
# vertex and triangle counts.
set(golden ${SOURCE}/tests/golden/v1/bordered-grid-3-levels)
file(STRINGS ${golden}.hashes recorded)
execute_process(COMMAND ${DBSS} info --hashes ${golden}.dbss OUTPUT_VARIABLE info_lines RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "info --hashes on ${golden}.dbss failed")
endif()
set(l 0)
foreach(hash ${recorded})
  if(NOT info_lines MATCHES "level ${l} vertices ([0-9]+) triangles ([0-9]+) fnv1a64 ${hash}")
    message(FATAL_ERROR "info --hashes has no level ${l} line with the recorded hash ${hash}:\n${info_lines}")
  endif()
  set(want "vertices ${CMAKE_MATCH_1} triangles ${CMAKE_MATCH_2} fnv1a64 ${hash}")
  foreach(ext ply obj off glb gltf)
    expect_run(0 "level ${l}" ${DBSS} decode ${golden}.dbss -o ${WORK}/geometry.${ext} --level ${l})
    execute_process(COMMAND ${MESH_HASH} ${WORK}/geometry.${ext} OUTPUT_VARIABLE got OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT got STREQUAL want)
      message(FATAL_ERROR "decode --level ${l} -o .${ext}: read back '${got}', the level is '${want}'")
    endif()
  endforeach()
  math(EXPR l "${l} + 1")
endforeach()

# `dbss export`: every level of a golden file in one GLB (and one .gltf),
# each level of detail stored as `dbss decode` gives it: gltf_lods lists the
# scene's node and then its MSFT_lod levels, finest first, each with the
# level's recorded hash and counts.  The files stay in ${WORK} for the glTF
# validator step of scripts/test.sh.
foreach(name bordered-grid-3-levels torus-4-levels)
  set(golden ${SOURCE}/tests/golden/v1/${name})
  file(STRINGS ${golden}.hashes recorded)
  execute_process(COMMAND ${DBSS} info --hashes ${golden}.dbss OUTPUT_VARIABLE info_lines)
  list(LENGTH recorded n)
  math(EXPR finest "${n} - 1")
  set(want "")
  foreach(l RANGE ${finest} 0 -1)
    list(GET recorded ${l} hash)
    string(REGEX MATCH "level ${l} vertices [0-9]+ triangles [0-9]+" counts "${info_lines}")
    set(want "${want}${counts} indices uint16 fnv1a64 ${hash}\n")
  endforeach()
  foreach(ext glb gltf)
    expect_run(0 "levels 0..${finest} " ${DBSS} export ${golden}.dbss -o ${WORK}/export-${name}.${ext})
    execute_process(COMMAND ${GLTF_LODS} ${WORK}/export-${name}.${ext} OUTPUT_VARIABLE got RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0 OR NOT got STREQUAL want)
      message(FATAL_ERROR "export ${name}.${ext}: levels of detail\n${got}\nexpected\n${want}")
    endif()
  endforeach()
endforeach()
# A range: the finest of it in the scene, the rest after it; one level alone.
expect_run(0 "levels 1..2 " ${DBSS} export ${golden}.dbss -o ${WORK}/export-1-2.glb --levels 1..2)
execute_process(COMMAND ${GLTF_LODS} ${WORK}/export-1-2.glb OUTPUT_VARIABLE got)
if(NOT got MATCHES "^level 2 vertices [0-9]+ triangles [0-9]+ indices uint16 fnv1a64 [0-9a-f]+\nlevel 1 vertices [^\n]*\n$")
  message(FATAL_ERROR "export --levels 1..2 wrote:\n${got}")
endif()
expect_run(0 "levels 3..3 " ${DBSS} export ${golden}.dbss -o ${WORK}/export-3.glb --levels 3)
# --draco: the coarser levels Draco-compressed (the validator checks the
# file's structure; io_tests decodes the Draco levels), a smaller file.
expect_run(0 "levels 0..4 " ${DBSS} export ${golden}.dbss -o ${WORK}/export-draco.glb --draco 12)
file(SIZE ${WORK}/export-draco.glb draco_size)
file(SIZE ${WORK}/export-torus-4-levels.glb plain_size)
if(NOT draco_size LESS plain_size)
  message(FATAL_ERROR "export --draco 12 wrote ${draco_size} bytes, the plain export ${plain_size}")
endif()
expect_run(1 "uses Draco-compressed meshes" ${DBSS} encode ${WORK}/export-draco.glb -o ${WORK}/x.dbss)
expect_run(1 "--draco needs a whole number" ${DBSS} export ${golden}.dbss -o ${WORK}/x.glb --draco 2)
expect_run(0 "usage: dbss export" ${DBSS} export --help)
expect_run(1 "no output file" ${DBSS} export ${golden}.dbss)
expect_run(1 "must be a .glb or .gltf file" ${DBSS} export ${golden}.dbss -o ${WORK}/x.ply)
expect_run(1 "--levels needs A..B" ${DBSS} export ${golden}.dbss -o ${WORK}/x.glb --levels 3..1)
expect_run(1 "--levels needs A..B" ${DBSS} export ${golden}.dbss -o ${WORK}/x.glb --levels 1..x)
expect_run(1 "level 5 is not in the file" ${DBSS} export ${golden}.dbss -o ${WORK}/x.glb --levels 0..5)
expect_run(1 "${WORK}/missing.dbss: cannot open" ${DBSS} export ${WORK}/missing.dbss -o ${WORK}/x.glb)
if(EXISTS ${WORK}/x.glb)
  message(FATAL_ERROR "a failed export left ${WORK}/x.glb behind")
endif()
# A cut file exports the levels verified before the cut, with a warning;
# asking for a later level fails.
file(SIZE ${golden}.dbss n)
if(HEAD)
  math(EXPR bytes "${n} * 3 / 4")
  execute_process(COMMAND ${HEAD} -c ${bytes} ${golden}.dbss OUTPUT_FILE ${WORK}/cut-torus.dbss)
  expect_run(0 "warning: .*truncated" ${DBSS} export ${WORK}/cut-torus.dbss -o ${WORK}/export-cut.glb)
  expect_run(1 "level 4 is not available" ${DBSS} export ${WORK}/cut-torus.dbss -o ${WORK}/x.glb --levels 0..4)
endif()
# glTF in: a damaged GLB is refused by name.
# (removed after, so only files dbss wrote are left for the validator).
file(WRITE ${WORK}/bad.glb "glTF not really")
expect_run(1 "${WORK}/bad.glb: not a valid glTF file" ${DBSS} encode ${WORK}/bad.glb -o ${WORK}/x.dbss)
file(REMOVE ${WORK}/bad.glb)

# `dbss info --json` on a format 1.3 file: a level's bytes are its LEVL
# chunk and the BDRY chunk before it, and the BDRY's values are listed.
set(bordered ${SOURCE}/tests/golden/v1/bordered-grid-boundary-3-levels.dbss)
execute_process(COMMAND ${DBSS} info --json ${bordered} RESULT_VARIABLE rc OUTPUT_VARIABLE json)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "info --json ${bordered}: exit ${rc}")
endif()
string(JSON chunks LENGTH "${json}" chunks)
math(EXPR last "${chunks} - 1")
set(pending 0)
set(level 0)
set(seen_boundary 0)
foreach(i RANGE ${last})
  string(JSON type GET "${json}" chunks ${i} type)
  string(JSON length GET "${json}" chunks ${i} length)
  if(type STREQUAL "BDRY")
    math(EXPR pending "${pending} + ${length}")
  elseif(type STREQUAL "LEVL")
    math(EXPR level "${level} + 1")
    math(EXPR want "${pending} + ${length}")
    string(JSON got GET "${json}" level_table ${level} bytes)
    if(NOT got EQUAL want)
      message(FATAL_ERROR "info --json ${bordered}: level ${level} bytes ${got}, its chunks hold ${want}")
    endif()
    if(pending GREATER 0)
      math(EXPR seen_boundary "${seen_boundary} + 1")
      string(JSON values GET "${json}" level_table ${level} boundary_values)
      if(NOT values GREATER 0)
        message(FATAL_ERROR "info --json ${bordered}: level ${level} has a BDRY chunk but boundary_values ${values}")
      endif()
    endif()
    set(pending 0)
  endif()
endforeach()
if(seen_boundary EQUAL 0)
  message(FATAL_ERROR "info --json ${bordered}: no level with a BDRY chunk")
endif()
