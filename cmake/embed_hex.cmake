# embed_hex.cmake — what the embedding scripts share (embed_glsl.cmake,
# embed_text.cmake): a file's bytes as C hex initialisers, and writing a
# generated file only when its text changed (so dependants do not rebuild).

# embed_hex(FILE OUTVAR): OUTVAR = "0x..,0x..," for every byte of FILE,
# sixteen to a line.
function(embed_hex file outvar)
  file(READ ${file} hex HEX)
  string(REGEX REPLACE "([0-9a-f][0-9a-f])" "0x\\1," hex "${hex}")
  string(REGEX REPLACE "(0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,0x..,)" "\\1\n" hex "${hex}")
  set(${outvar} "${hex}" PARENT_SCOPE)
endfunction()

# embed_write(OUT BODY): writes BODY to OUT unless OUT already holds it.
function(embed_write out body)
  if(EXISTS ${out})
    file(READ ${out} old)
    if(old STREQUAL body)
      return()
    endif()
  endif()
  file(WRITE ${out} "${body}")
endfunction()
