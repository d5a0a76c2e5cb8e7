#include "robot_log.h"

#include <iomanip>
#include <sstream>

std::string FormatPosition(const argos::CVector3& c_position) {
    std::ostringstream stream;
    stream << std::fixed << std::setprecision(4) << c_position.GetX() << "," << c_position.GetY();
    return stream.str();
}
