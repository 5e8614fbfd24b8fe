/* stb_write.h - stb_image_write from Debian's libstb-dev, compiled into the program that
   includes this file (once per program), with the warnings fogrt's flags (-Wall -Wextra
   -pedantic -Wshadow ...) would raise in the third-party header silenced for it alone.
     FOGRT_STB_READ_HDR   also stb_image, for Radiance .hdr files only (the fogrt command's -e)
     FOGRT_STB_EASY_FONT  also stb_easy_font (the preview's help overlay)                   */
#ifndef FOGRT_EXAMPLES_STB_WRITE_H
#define FOGRT_EXAMPLES_STB_WRITE_H
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#ifdef FOGRT_STB_READ_HDR
#define STB_IMAGE_IMPLEMENTATION       /* (not static: gcc warns about its unused declarations) */
#define STBI_ONLY_HDR
#include <stb/stb_image.h>
#endif
#ifdef FOGRT_STB_EASY_FONT
#include <stb/stb_easy_font.h>
#endif
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
#endif
