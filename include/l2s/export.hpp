#pragma once
// Which declarations leave the shared libraries. Every library of l2scalib is
// built with hidden symbols; a public class or function carries the macro of
// the library that defines it:
//   L2S_EXPORT        l2scalib (core)     L2S_SIM_EXPORT    l2scalib::sim
//   L2S_SUITE_EXPORT  l2scalib::suite     L2S_VIZ_EXPORT    l2scalib::viz
//   L2S_PCL_EXPORT    l2scalib::pcl
// On ELF and Mach-O every macro means default visibility, in shared and
// static builds alike (so both compile identically and share a compiler
// cache). Windows needs dllexport while a DLL is built and dllimport when it
// is used: CMake defines <target>_EXPORTS for the first, and static builds
// define L2S_STATIC for themselves and their users.

#if !defined(_WIN32) && !defined(__CYGWIN__)
#define L2S_EXPORT __attribute__((visibility("default")))
#define L2S_SIM_EXPORT L2S_EXPORT
#define L2S_SUITE_EXPORT L2S_EXPORT
#define L2S_VIZ_EXPORT L2S_EXPORT
#define L2S_PCL_EXPORT L2S_EXPORT
#elif defined(L2S_STATIC)
#define L2S_EXPORT
#define L2S_SIM_EXPORT
#define L2S_SUITE_EXPORT
#define L2S_VIZ_EXPORT
#define L2S_PCL_EXPORT
#else
#ifdef l2scalib_EXPORTS
#define L2S_EXPORT __declspec(dllexport)
#else
#define L2S_EXPORT __declspec(dllimport)
#endif
#ifdef l2scalib_sim_EXPORTS
#define L2S_SIM_EXPORT __declspec(dllexport)
#else
#define L2S_SIM_EXPORT __declspec(dllimport)
#endif
#ifdef l2scalib_suite_EXPORTS
#define L2S_SUITE_EXPORT __declspec(dllexport)
#else
#define L2S_SUITE_EXPORT __declspec(dllimport)
#endif
#ifdef l2scalib_viz_EXPORTS
#define L2S_VIZ_EXPORT __declspec(dllexport)
#else
#define L2S_VIZ_EXPORT __declspec(dllimport)
#endif
#ifdef l2scalib_pcl_EXPORTS
#define L2S_PCL_EXPORT __declspec(dllexport)
#else
#define L2S_PCL_EXPORT __declspec(dllimport)
#endif
#endif
