// The scripted mode's options for the report windows (tests, screenshots): open the anti-aliasing report,
// the grid sweep or the bounding-volume report on the scene, run it and wait for it, cancel it after a row,
// choose a density on the sweep's slider, and write the windows' screenshots and state. script.cpp calls
// these at its steps.
//   raystep-gui SCENE --report aa [--report-methods LIST] [--report-size WxH] [--report-seeds N]
//               [--report-reference REF] [--report-axis rays|time] --screenshot-report out.png --quit
//   raystep-gui SCENE --report grid-sweep [--sweep-densities LIST] [--sweep-choose D]
//               --screenshot-sweep out.png --dump-state state.json --quit
//   raystep-gui SCENE --report bvol --screenshot-bvol out.png --quit
#pragma once

#include <QJsonObject>
#include <QStringList>

class QCommandLineParser;

namespace raystep::viz {

class MainWindow;

void defineReportOptions(QCommandLineParser& p);
QStringList reportScriptOptions();  // the options that make a run scripted
// After the state is entered: opens, runs and waits for the reports asked for (throws InputError).
void runReportActions(MainWindow& window, const QCommandLineParser& p);
void writeReportOutputs(MainWindow& window, const QCommandLineParser& p);
// The report windows' state and the grid the main window holds, added to the state dump.
void addReportState(MainWindow& window, QJsonObject& o);

}  // namespace raystep::viz
