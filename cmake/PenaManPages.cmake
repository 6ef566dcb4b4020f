# Manual pages: help2man turns each installed program's --help into <program>.1.gz (share/man/man1),
# built with the program and installed with it (component tools or services). Without help2man
# (scripts/setup.sh installs it) the programs install without pages.
find_program(PENA_HELP2MAN help2man)

# pena_man_page(<target> <component> <one-line description>)
function(pena_man_page target component description)
  if(NOT PENA_HELP2MAN)
    return()
  endif()
  set(page ${PROJECT_BINARY_DIR}/man/${target}.1)
  # Run as plain "<target>" from PATH, so the usage line names the program, not the build tree.
  add_custom_command(OUTPUT ${page}.gz
    COMMAND ${CMAKE_COMMAND} -E make_directory ${PROJECT_BINARY_DIR}/man
    COMMAND ${CMAKE_COMMAND} -E env "PATH=$<TARGET_FILE_DIR:${target}>:/usr/bin:/bin"
            ${PENA_HELP2MAN} --no-info --no-discard-stderr --section=1 --source=PeNa
            --version-string=${PROJECT_VERSION} --name=${description} --output=${page} ${target}
    COMMAND gzip -9nf ${page}
    DEPENDS ${target}
    COMMENT "help2man ${target}"
    VERBATIM)
  add_custom_target(${target}_man ALL DEPENDS ${page}.gz)
  install(FILES ${page}.gz DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT ${component})
endfunction()
