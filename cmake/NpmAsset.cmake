# NpmAsset.cmake — one file of a package from the npm registry, fetched at configure time, checked
# against a pinned SHA-512 (npm's own "integrity" of the tarball, in hex) and extracted into the build
# tree, for embedding into the binary. Nothing is loaded from a CDN and nothing unpinned is accepted.
#
#   vobench_npm_asset(<out-var> PACKAGE <name> VERSION <x.y.z> SHA512 <hex> FILE <path in tarball>)
#
# <out-var> is set to the extracted file's path. Where the tarball comes from:
#   VOBENCH_NPM_REGISTRY  the registry (default https://registry.npmjs.org); any URL cmake can read,
#                         so an air-gapped site points it at a mirror (file:///srv/npm works too,
#                         laid out as the registry is: <name>/-/<name>-<version>.tgz).
# A tarball already in the build tree with the right hash is not fetched again.

if(NOT DEFINED VOBENCH_NPM_REGISTRY)
  set(VOBENCH_NPM_REGISTRY "https://registry.npmjs.org" CACHE STRING "npm registry the report's JavaScript is fetched from")
endif()

function(vobench_npm_asset out_var)
  cmake_parse_arguments(A "" "PACKAGE;VERSION;SHA512;FILE" "" ${ARGN})
  foreach(arg PACKAGE VERSION SHA512 FILE)
    if(NOT A_${arg})
      message(FATAL_ERROR "vobench_npm_asset: ${arg} missing")
    endif()
  endforeach()
  set(dir "${CMAKE_BINARY_DIR}/_npm/${A_PACKAGE}-${A_VERSION}")
  set(tarball "${dir}/${A_PACKAGE}-${A_VERSION}.tgz")
  set(url "${VOBENCH_NPM_REGISTRY}/${A_PACKAGE}/-/${A_PACKAGE}-${A_VERSION}.tgz")
  set(extracted "${dir}/${A_FILE}")
  if(EXISTS "${tarball}")
    file(SHA512 "${tarball}" have)
    if(NOT have STREQUAL A_SHA512)
      file(REMOVE "${tarball}" "${extracted}")
    endif()
  endif()
  if(NOT EXISTS "${tarball}")
    message(STATUS "Fetching ${A_PACKAGE}@${A_VERSION} from ${url}")
    file(DOWNLOAD "${url}" "${tarball}.part" STATUS status TLS_VERIFY ON INACTIVITY_TIMEOUT 60 TIMEOUT 300)
    list(GET status 0 code)
    if(NOT code EQUAL 0)
      list(GET status 1 why)
      file(REMOVE "${tarball}.part")
      message(FATAL_ERROR "Could not fetch ${A_PACKAGE}@${A_VERSION} from ${url}: ${why}.\n"
                          "The report embeds it (pinned by SHA-512); point -DVOBENCH_NPM_REGISTRY=URL at a mirror that has it.")
    endif()
    file(SHA512 "${tarball}.part" have)
    if(NOT have STREQUAL A_SHA512)
      file(REMOVE "${tarball}.part")
      message(FATAL_ERROR "${A_PACKAGE}@${A_VERSION} from ${url}: SHA-512 mismatch (got ${have}, pinned ${A_SHA512}); refused.")
    endif()
    file(RENAME "${tarball}.part" "${tarball}")
  endif()
  if(NOT EXISTS "${extracted}")
    file(ARCHIVE_EXTRACT INPUT "${tarball}" DESTINATION "${dir}" PATTERNS "${A_FILE}")
    if(NOT EXISTS "${extracted}")
      message(FATAL_ERROR "${A_PACKAGE}@${A_VERSION}: ${A_FILE} is not in ${tarball}")
    endif()
  endif()
  set(${out_var} "${extracted}" PARENT_SCOPE)
endfunction()
