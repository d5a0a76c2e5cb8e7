"""The generated ARGoS project builds with its own CMakeLists.txt against real ARGoS, with g++
(ARGoS found from ARGOS_PREFIX) and clang++ (from ARGoS_DIR), -Wall -Wextra -pedantic -Werror
and no warning: ARGoS's headers, and Lua's that ARGoS built with Lua includes, are system
headers."""

import pytest

pytestmark = [pytest.mark.emulator, pytest.mark.slow]


@pytest.mark.parametrize("built", ["energy_worker", "network_worker"])
def test_controller_builds_warning_free(request, built, argos_prefix):
    project, log = request.getfixturevalue(built)
    assert (project.folder / "build" / ("lib%s_controller.so" % project.name)).is_file()
    assert "warning" not in log.lower(), log
    assert "-isystem %s/include" % argos_prefix in log
    settings = (argos_prefix / "share" / "argos3" / "cmake" / "ARGoSSettings.cmake").read_text()
    if "set(ARGOS_WITH_LUA ON)" in settings:
        assert "-isystem /usr/include/lua5.3" in log
