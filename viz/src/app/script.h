// The command line of raystep-gui and its scripted mode (tests, docs, slides): open, build, trace a pixel,
// step, then write a screenshot and the drawn state and quit, exactly as a user would have seen it.
//   raystep-gui SCENE|TRACE [--grid-res NX,NY,NZ] [--grid-density D] [--grid-insert exact|bbox]
//               [--pixel X,Y] [--step N | --step-to KIND:K] [--size WxH] --screenshot out.png --quit
//   kd-tree: [--accel kd] [--panel sah] [--node ID | --node-path LRL] [--pick-3d X,Y] [--export-sah curve.csv]
//            [--screenshot-sah chart.png]
// Any error in scripted mode prints one line "error: FILE:LINE: what" and exits with code 2.
#pragma once

#include <QStringList>

namespace raystep::viz {

class MainWindow;

// With --help (or -h) among the arguments: prints the usage and returns true. Needs no display: a
// QCoreApplication will do.
bool printHelpIfAsked(const QStringList& arguments);
// Parses the arguments and runs what they ask; returns -1 to go on interactively, else the exit code.
int runCommandLine(MainWindow& window, const QStringList& arguments);

}  // namespace raystep::viz
