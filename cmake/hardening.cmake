# Hardening build flags, as Debian's dpkg-buildflags gives them with "hardening=+all": buffer
# overflow checks in libc calls (_FORTIFY_SOURCE, which needs the optimizer), stack protector,
# a read-only GOT bound at start-up (relro, now) and position-independent executables (PIE).
# Flags a packager passes (CFLAGS/CXXFLAGS/LDFLAGS from dpkg-buildflags) come on top of these.
# Not in sanitizer builds (the sanitizers replace the libc checks) nor in the static build
# (the VM test's initramfs: a static PIE needs a libc built for it).
option(STEPMOD_HARDENING "Build with the hardening flags of dpkg-buildflags" ON)
if(STEPMOD_HARDENING AND STEPMOD_SANITIZE STREQUAL "" AND NOT STEPMOD_STATIC)
  include(CheckPIESupported)
  check_pie_supported()
  set(CMAKE_POSITION_INDEPENDENT_CODE ON)
  # -U first: a toolchain that already defines another level must not make this a redefinition.
  add_compile_options(-fstack-protector-strong -fstack-clash-protection
    "$<$<NOT:$<CONFIG:Debug>>:-U_FORTIFY_SOURCE;-D_FORTIFY_SOURCE=2>")
  add_link_options(-Wl,-z,relro -Wl,-z,now)
endif()
