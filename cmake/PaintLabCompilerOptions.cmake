# Compiler options shared by every PaintLab target.
# paintlab_set_target_options(<target>) applies warnings (as errors when
# PAINTLAB_WERROR is on), the sanitizers when PAINTLAB_SANITIZE is on, and
# otherwise the hardening Debian builds its packages with.

add_library(paintlab_compiler_options INTERFACE)
target_compile_options(paintlab_compiler_options INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast
  -Wcast-align -Woverloaded-virtual -Wconversion -Wsign-conversion
  -Wnull-dereference -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
if(PAINTLAB_WERROR)
  target_compile_options(paintlab_compiler_options INTERFACE -Werror)
endif()
if(PAINTLAB_SANITIZE)
  # One sanitizer configuration (address + undefined), as pbrt's CI matrix has;
  # UB is made fatal so a CTest run fails on the first report.
  target_compile_options(paintlab_compiler_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(paintlab_compiler_options INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all)
endif()

if(NOT PAINTLAB_SANITIZE)
  # dpkg-buildflags' hardening (fortified libc calls, stack protector, read-only
  # relocations) plus bind-now, so the package passes lintian's hardening
  # checks. _FORTIFY_SOURCE needs optimisation; ASan replaces these checks.
  target_compile_definitions(paintlab_compiler_options INTERFACE
    $<$<NOT:$<CONFIG:Debug>>:_FORTIFY_SOURCE=2>)
  target_compile_options(paintlab_compiler_options INTERFACE -fstack-protector-strong)
  target_link_options(paintlab_compiler_options INTERFACE LINKER:-z,relro LINKER:-z,now)
endif()

function(paintlab_set_target_options target)
  target_link_libraries(${target} PRIVATE paintlab_compiler_options)
endfunction()
