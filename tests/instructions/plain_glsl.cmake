# plain_glsl.cmake — a test-only copy of techniques/glsl/ whose vt.glsl is
# replaced by VT_FILE (tests/instructions/plain_vt.glsl: the maps as plain
# textures, no virtual-texturing code), embedded like the real one.  Only
# the test binary dmbench_plainshader links the generated table.
#   cmake -DGLSL_DIR=<techniques/glsl> -DOUT_DIR=<dir> -DVT_FILE=<file> -P plain_glsl.cmake
if(NOT GLSL_DIR OR NOT OUT_DIR OR NOT VT_FILE)
  message(FATAL_ERROR "plain_glsl.cmake: set GLSL_DIR, OUT_DIR and VT_FILE")
endif()
file(MAKE_DIRECTORY ${OUT_DIR})
file(GLOB files RELATIVE ${GLSL_DIR} ${GLSL_DIR}/*.glsl)
foreach(f ${files})
  if(f STREQUAL "vt.glsl")
    file(READ ${VT_FILE} text)
  else()
    file(READ ${GLSL_DIR}/${f} text)
  endif()
  set(old "")
  if(EXISTS ${OUT_DIR}/${f})
    file(READ ${OUT_DIR}/${f} old)
  endif()
  if(NOT old STREQUAL text)
    file(WRITE ${OUT_DIR}/${f} "${text}")
  endif()
endforeach()
