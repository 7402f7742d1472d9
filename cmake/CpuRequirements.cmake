# Writes OUT: the Linux /proc/cpuinfo flags a CPU needs to run code compiled with -march=${ARCH}, one per line,
# from the feature macros the compiler defines for that target. The add-on checks them before it imports the
# native module (addon/candela/native.py): an instruction the CPU lacks would kill Blender with SIGILL.
function(candela_cpu_requirements compiler arch out)
  execute_process(COMMAND ${compiler} -march=${arch} -dM -E -x c++ /dev/null
                  OUTPUT_VARIABLE macros RESULT_VARIABLE rc ERROR_QUIET)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "cannot list the features of -march=${arch}")
  endif()
  # compiler macro → cpuinfo flag
  set(map
    __SSE3__=pni __SSSE3__=ssse3 __SSE4_1__=sse4_1 __SSE4_2__=sse4_2 __POPCNT__=popcnt __AVX__=avx __AVX2__=avx2
    __FMA__=fma __BMI__=bmi1 __BMI2__=bmi2 __F16C__=f16c __LZCNT__=abm __MOVBE__=movbe __XSAVE__=xsave
    __AVX512F__=avx512f __AVX512CD__=avx512cd __AVX512BW__=avx512bw __AVX512DQ__=avx512dq __AVX512VL__=avx512vl
    __AVX512VNNI__=avx512_vnni __AVX512BF16__=avx512_bf16 __AVX512IFMA__=avx512ifma __AVX512VBMI__=avx512vbmi
    __AVX512VBMI2__=avx512_vbmi2 __AVX512BITALG__=avx512_bitalg __AVX512VPOPCNTDQ__=avx512_vpopcntdq
    __AVX512FP16__=avx512_fp16 __AVXVNNI__=avx_vnni __SHA__=sha_ni __AES__=aes __PCLMUL__=pclmulqdq
    __VAES__=vaes __VPCLMULQDQ__=vpclmulqdq __GFNI__=gfni __ADX__=adx __RDRND__=rdrand __RDSEED__=rdseed)
  set(flags "")
  foreach(pair ${map})
    string(REPLACE "=" ";" kv ${pair})
    list(GET kv 0 macro)
    list(GET kv 1 flag)
    if(macros MATCHES "#define ${macro} 1")
      string(APPEND flags "${flag}\n")
    endif()
  endforeach()
  file(WRITE ${out} "${flags}")
endfunction()
