# cmake -P script, run at build time (app/CMakeLists.txt): the manual pages casteljau(1) and
# casteljau-<command>(1), written from the program's own help texts so they never drift from
# them. `casteljau --help` gives the command list and summaries; `casteljau <command> --help`
# gives each page's usage lines (SYNOPSIS) and the rest (DESCRIPTION), kept preformatted as
# the help is laid out in columns.
# Inputs (-D): CJ_EXE (the built tool), CJ_OUT (folder for the pages), CJ_VERSION.
cmake_minimum_required(VERSION 3.20)
foreach(v CJ_EXE CJ_OUT CJ_VERSION)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "CjManPages.cmake: ${v} is not set")
  endif()
endforeach()

# Lines of help text as roff: backslashes doubled into \e, a leading . or ' made literal.
function(cj_roff_escape var text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  set(${var} "${text}" PARENT_SCOPE)
endfunction()

function(cj_help var)
  execute_process(COMMAND ${CJ_EXE} ${ARGN} --help RESULT_VARIABLE rc OUTPUT_VARIABLE out
    ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR out STREQUAL "")
    message(FATAL_ERROR "'casteljau ${ARGN} --help' failed (${rc}): ${err}")
  endif()
  string(REGEX REPLACE "\n+$" "" out "${out}")
  set(${var} "${out}" PARENT_SCOPE)
endfunction()

# Splits a help text into its leading usage lines (the "usage:" lines and their continuations,
# indented under the first) and the rest. Lines go through CMake lists, so ; [ and ] (list
# syntax) travel as placeholders.
function(cj_lines var text)
  string(REPLACE ";" "@CJ_SEMI@" text "${text}")
  string(REPLACE "[" "@CJ_LB@" text "${text}")
  string(REPLACE "]" "@CJ_RB@" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(${var} "${lines}" PARENT_SCOPE)
endfunction()
function(cj_unlines var)
  string(JOIN "\n" text ${ARGN})
  string(REPLACE "@CJ_SEMI@" ";" text "${text}")
  string(REPLACE "@CJ_LB@" "[" text "${text}")
  string(REPLACE "@CJ_RB@" "]" text "${text}")
  set(${var} "${text}" PARENT_SCOPE)
endfunction()
function(cj_split_usage text usage_var rest_var)
  cj_lines(lines "${text}")
  set(usage)
  set(rest)
  set(in_usage ON)
  foreach(line IN LISTS lines)
    if(in_usage AND line MATCHES "^usage: ")
      string(SUBSTRING "${line}" 7 -1 line)
      list(APPEND usage "${line}")
    elseif(in_usage AND usage AND line MATCHES "^       ")
      string(SUBSTRING "${line}" 7 -1 line)
      list(APPEND usage "${line}")
    else()
      set(in_usage OFF)
      list(APPEND rest "${line}")
    endif()
  endforeach()
  cj_unlines(usage ${usage})
  cj_unlines(rest ${rest})
  string(REGEX REPLACE "^\n+" "" rest "${rest}")
  set(${usage_var} "${usage}" PARENT_SCOPE)
  set(${rest_var} "${rest}" PARENT_SCOPE)
endfunction()

file(MAKE_DIRECTORY ${CJ_OUT})
cj_help(main)
# The command table: the lines between "commands:" and the next blank line.
string(REGEX MATCH "commands:\n(( +[a-z]+ +[^\n]*\n)+)" block "${main}\n")
cj_lines(command_lines "${CMAKE_MATCH_1}")
set(commands)
set(see_also "casteljau(1)")
set(main_commands "")
foreach(line IN LISTS command_lines)
  if(line MATCHES "^ +([a-z]+) +(.*)$")
    set(name "${CMAKE_MATCH_1}")
    cj_unlines(summary "${CMAKE_MATCH_2}")
    list(APPEND commands ${name})
    set(summary_${name} "${summary}")
    cj_roff_escape(esc "${summary}")
    string(APPEND main_commands ".TP\n.B ${name}\n${esc} (see\n.BR casteljau-${name} (1))\n")
  endif()
endforeach()
if(NOT commands)
  message(FATAL_ERROR "no command list in 'casteljau --help':\n${main}")
endif()
string(REGEX REPLACE "^.*\ncommands:\n( +[a-z]+ +[^\n]*\n)+\n?" "" main_tail "${main}\n")
cj_roff_escape(main_tail "${main_tail}")

set(header_date "")
set(all_refs "")
foreach(name IN LISTS commands)
  string(APPEND all_refs ".BR casteljau-${name} (1)\n")
endforeach()
file(WRITE ${CJ_OUT}/casteljau.1
  ".\\\" Written at build time from 'casteljau --help' by cmake/CjManPages.cmake: do not edit.\n"
  ".TH CASTELJAU 1 \"\" \"casteljau ${CJ_VERSION}\" \"casteljau manual\"\n"
  ".SH NAME\ncasteljau \\- curves and surfaces: evaluate, interpolate, tessellate, render\n"
  ".SH SYNOPSIS\n.B casteljau\n.I command\n[options]\n.br\n.B casteljau --help\n.br\n"
  ".B casteljau --version\n"
  ".SH COMMANDS\n${main_commands}"
  ".SH DESCRIPTION\n.nf\n${main_tail}.fi\n"
  ".SH SEE ALSO\n${all_refs}")

foreach(name IN LISTS commands)
  cj_help(help ${name})
  cj_split_usage("${help}" usage rest)
  cj_roff_escape(usage "${usage}")
  cj_roff_escape(rest "${rest}")
  cj_roff_escape(summary "${summary_${name}}")
  string(TOUPPER "casteljau-${name}" title)
  file(WRITE ${CJ_OUT}/casteljau-${name}.1
    ".\\\" Written at build time from 'casteljau ${name} --help' by cmake/CjManPages.cmake: do not edit.\n"
    ".TH ${title} 1 \"\" \"casteljau ${CJ_VERSION}\" \"casteljau manual\"\n"
    ".SH NAME\ncasteljau-${name} \\- ${summary}\n"
    ".SH SYNOPSIS\n.nf\n${usage}\n.fi\n"
    ".SH DESCRIPTION\n.nf\n${rest}\n.fi\n"
    ".SH SEE ALSO\n.BR casteljau (1)\n")
endforeach()
list(LENGTH commands n)
message(STATUS "manual pages: casteljau(1) and ${n} command pages in ${CJ_OUT}")
