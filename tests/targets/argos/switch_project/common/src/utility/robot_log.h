#ifndef ROBOT_LOG_H
#define ROBOT_LOG_H

#include <string>

#include <argos3/core/utility/math/vector3.h>

/* A position as the logs print it: x and y, 4 decimals */
std::string FormatPosition(const argos::CVector3& c_position);

#endif
