# slow_glsl.cmake — a test-only copy of techniques/glsl/ in which one stage
# family does a little more arithmetic (the "slower shader" of the
# Instructions gate tests), embedded like the real one.  Production builds
# never see it: only the test binaries dmbench_slow*shader link the
# generated table.
#   FAMILY fragment (default): surface.frag.glsl, every technique's fragment stage
#   FAMILY vertex:             displace.vert.glsl, vertex-displacement's vertex stage
#   FAMILY tess:               tess.tes.glsl, tess-displacement's evaluation stage
#   FAMILY plainvt:            vt.glsl replaced by VT_FILE (no virtual-texturing
#                              code: dmbench_plainshader of test_instructions_uber)
#   cmake -DGLSL_DIR=<techniques/glsl> -DOUT_DIR=<dir> -DSTEPS=<n> [-DFAMILY=f] -P slow_glsl.cmake
#   cmake -DGLSL_DIR=<techniques/glsl> -DOUT_DIR=<dir> -DFAMILY=plainvt -DVT_FILE=<file> -P slow_glsl.cmake
if(NOT GLSL_DIR OR NOT OUT_DIR OR (NOT STEPS AND NOT FAMILY STREQUAL "plainvt"))
  message(FATAL_ERROR "slow_glsl.cmake: set GLSL_DIR, OUT_DIR and STEPS")
endif()
if(NOT FAMILY)
  set(FAMILY fragment)
endif()
# Per family: the file, the text the steps go before, and the steps.  Each
# step feeds the stage's output, so the compiler cannot drop it, and
# changes it by < 1e-6.
if(FAMILY STREQUAL "fragment")
  set(target "surface.frag.glsl")
  set(anchor "    o_color = vec4(c, 1.0);\n#endif\n}")
  set(steps "    for (int k = 0; k < ${STEPS}; k++)\n        c = c + 1e-7 * sin(c * 1.7 + float(k));\n")
elseif(FAMILY STREQUAL "vertex")
  set(target "displace.vert.glsl")
  set(anchor "    displace_emit(displace_point(a_pos, a_nrm, h), a_uv, a_nrm, a_tan);\n#endif\n}")
  set(steps "    for (int k = 0; k < ${STEPS}; k++)\n        h = h + 1e-9 * sin(h * 1.7 + float(k));\n")
elseif(FAMILY STREQUAL "tess")
  set(target "tess.tes.glsl")
  set(anchor "    displace_emit(displace_point(p, dn, h), uv, n, t);\n}")
  set(steps "    for (int k = 0; k < ${STEPS}; k++)\n        h = h + 1e-9 * sin(h * 1.7 + float(k));\n")
elseif(FAMILY STREQUAL "plainvt" AND VT_FILE)
  set(target "vt.glsl")
else()
  message(FATAL_ERROR "slow_glsl.cmake: FAMILY must be fragment, vertex, tess or plainvt (with VT_FILE)")
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
file(GLOB files RELATIVE ${GLSL_DIR} ${GLSL_DIR}/*.glsl)
foreach(f ${files})
  file(READ ${GLSL_DIR}/${f} text)
  if(f STREQUAL target AND FAMILY STREQUAL "plainvt")
    file(READ ${VT_FILE} text)
  elseif(f STREQUAL target)
    string(FIND "${text}" "${anchor}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "slow_glsl.cmake: the end of main() in ${f} changed; update the anchor")
    endif()
    string(REPLACE "${anchor}" "${steps}${anchor}" text "${text}")
  endif()
  set(old "")
  if(EXISTS ${OUT_DIR}/${f})
    file(READ ${OUT_DIR}/${f} old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE ${OUT_DIR}/${f} "${text}")
  endif()
endforeach()
