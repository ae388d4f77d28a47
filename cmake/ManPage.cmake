# Run at build time (cmake -P, from app/CMakeLists.txt): writes OUT, the gzipped manual page of
# the program NAME in BIN_DIR, from what the program prints: its --version, its --help, and a
# section per command from each command's own --help, found by walking the "Subcommands:" lists
# of CLI11's help (a new command is in the page without a list here). The help is kept as
# printed, preformatted: help2man re-flowed the examples into one paragraph.
# SUMMARY is the page's one-line description.
set(ENV{PATH} "${BIN_DIR}:$ENV{PATH}")  # run by name: the usage lines say `boneless-cli`, no path

function(run out_var)
  execute_process(COMMAND ${NAME} ${ARGN} OUTPUT_VARIABLE output ERROR_VARIABLE output
                  RESULT_VARIABLE failed)
  if(failed)
    string(REPLACE ";" " " command "${NAME} ${ARGN}")
    message(FATAL_ERROR "${command} failed: ${output}")
  endif()
  set(${out_var} "${output}" PARENT_SCOPE)
endfunction()

# roff, preformatted: a backslash, or a "." or "'" starting a line, stays text.
function(preformatted out_var text)
  string(STRIP "${text}" text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REPLACE "\n" "\n\\&" text "\\&${text}")
  set(${out_var} ".nf\n${text}\n.fi\n" PARENT_SCOPE)
endfunction()

function(walk page_var command)
  run(help ${command} --help)
  set(page "${${page_var}}")
  if(command)
    # The footer every command repeats is in the page once, under USAGE.
    string(REGEX REPLACE "\nA take from the capture.*" "" help "${help}")
    string(JOIN " " title ${NAME} ${command})  # unquoted: the empty first element goes
    preformatted(text "${help}")
    string(APPEND page ".SS \"${title}\"\n${text}")
  endif()
  string(REGEX MATCH "\nSubcommands:\n(  [^\n]*\n)+" list "${help}")
  string(REGEX MATCHALL "\n  [a-z][a-z0-9-]*" subs "${list}")
  foreach(sub IN LISTS subs)
    string(STRIP "${sub}" sub)
    walk(page "${command};${sub}")
  endforeach()
  set(${page_var} "${page}" PARENT_SCOPE)
endfunction()

run(version --version)
string(STRIP "${version}" version)
string(TOUPPER "${NAME}" title)
run(help --help)
preformatted(usage "${help}")
set(commands "")
walk(commands "")
string(CONCAT page ".TH \"${title}\" 1 \"\" \"${version}\" \"User Commands\"\n"
                   ".SH NAME\n${NAME} \\- ${SUMMARY}\n.SH USAGE\n${usage}")
if(commands)
  string(APPEND page ".SH COMMANDS\n${commands}")
endif()
string(APPEND page ".SH \"SEE ALSO\"\nboneless(1), boneless-cli(1). The manual: "
                   "/usr/share/doc/boneless/README.md and the docs/ pages beside it.\n")
file(WRITE "${OUT}.tmp" "${page}")
# gzip -n: no name or time stamp inside, so the same page packs to the same bytes.
execute_process(COMMAND gzip -9nf "${OUT}.tmp" RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "gzip failed on ${OUT}.tmp")
endif()
file(RENAME "${OUT}.tmp.gz" "${OUT}")
