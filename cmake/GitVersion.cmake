# boneless_version(<var> <source dir> <version>): the version the binaries print and the package
# names. From a git checkout, <version>+git<commit date, UTC>.<hash>, so that a report names the
# commit and a package of a later commit upgrades an earlier one; otherwise <version>.
function(boneless_version var source version)
  set(result "${version}")
  find_package(Git QUIET)
  if(GIT_FOUND AND EXISTS "${source}/.git")
    set(ENV{TZ} UTC)
    execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${source}" log -1 --format=%cd.%h
                            --abbrev=7 --date=format-local:%Y%m%d.%H%M%S
                    OUTPUT_VARIABLE commit OUTPUT_STRIP_TRAILING_WHITESPACE
                    RESULT_VARIABLE failed ERROR_QUIET)
    if(NOT failed AND commit)
      set(result "${version}+git${commit}")
    endif()
  endif()
  set(${var} "${result}" PARENT_SCOPE)
endfunction()
