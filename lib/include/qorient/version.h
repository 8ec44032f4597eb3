/* qorient/version.h - library version (semantic versioning). */
#ifndef QORIENT_VERSION_H
#define QORIENT_VERSION_H
#define QO_VERSION_MAJOR 0
#define QO_VERSION_MINOR 1
#define QO_VERSION_PATCH 0
#define QO_VERSION_STRING "0.1.0"
#endif
