#ifndef TRACE_LOOP_FUNCTIONS_H
#define TRACE_LOOP_FUNCTIONS_H

#include <fstream>

#include <argos3/core/simulator/loop_functions.h>

using namespace argos;

/* Writes every robot's position after every step to a file, and a summary to the log */
class CTraceLoopFunctions : public CLoopFunctions {

public:

    virtual void Init(TConfigurationNode& t_tree);
    virtual void PostStep();
    virtual void PostExperiment();

private:

    std::ofstream m_cTrace;

};

#endif
