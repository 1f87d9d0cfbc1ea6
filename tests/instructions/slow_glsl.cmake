# slow_glsl.cmake — a test-only copy of techniques/glsl/ whose surface
# fragment shader does a little more arithmetic per fragment (the "slower
# shader" of the Instructions gate test), embedded like the real one.
# Production builds never see it: only the test binary dmbench_slowshader
# links the generated table.
#   cmake -DGLSL_DIR=<techniques/glsl> -DOUT_DIR=<dir> -DSTEPS=<n> -P slow_glsl.cmake
if(NOT GLSL_DIR OR NOT OUT_DIR OR NOT STEPS)
  message(FATAL_ERROR "slow_glsl.cmake: set GLSL_DIR, OUT_DIR and STEPS")
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
file(GLOB files RELATIVE ${GLSL_DIR} ${GLSL_DIR}/*.glsl)
foreach(f ${files})
  file(READ ${GLSL_DIR}/${f} text)
  if(f STREQUAL "surface.frag.glsl")
    set(anchor "    o_color = vec4(c, 1.0);\n#endif\n}")
    string(FIND "${text}" "${anchor}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "slow_glsl.cmake: the end of main() in ${f} changed; update the anchor")
    endif()
    # STEPS dependent steps per fragment; the result feeds the output, so the
    # compiler cannot drop them, and changes it by < 1e-6
    string(REPLACE "${anchor}"
      "    for (int k = 0; k < ${STEPS}; k++)\n        c = c + 1e-7 * sin(c * 1.7 + float(k));\n    o_color = vec4(c, 1.0);\n#endif\n}"
      text "${text}")
  endif()
  set(old "")
  if(EXISTS ${OUT_DIR}/${f})
    file(READ ${OUT_DIR}/${f} old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE ${OUT_DIR}/${f} "${text}")
  endif()
endforeach()
