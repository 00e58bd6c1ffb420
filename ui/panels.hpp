#pragma once
// Dear ImGui panels. Each edits a plain settings struct and records what the user asked
// for in UiRequests; the app acts on the requests and the renderer reads the structs.
// Nothing here issues GL calls.
#include <optional>
#include <string>
#include <vector>

#include "frame/camera.hpp"
#include "frame/debug_layout.hpp"
#include "ui/pareto_chart.hpp"
#include "frame/renderer.hpp"
#include "frame/settings.hpp"

namespace iblab::ui {

struct EnvironmentCatalog {
    std::vector<std::string> gallery;  // bundled files
    std::vector<std::string> builtins; // "builtin:white", ...
};

struct StatusLine {
    std::string text;
    bool isError = false;
    // Details that are worth knowing but are no problem (texels a loader repaired, a model's
    // unsupported extension): shown quietly under the line.
    std::vector<std::string> notes = {};
    // text and notes in one line ("a; b; c"), for logs and reports.
    std::string joined() const;
};

struct FrameStats {
    double frameMs = 0.0;  // wall clock of the whole frame, CPU side
    double renderMs = 0.0; // a full-resolution frame of the shown settings (ViewScheduler::fullFrameMs): measured, or a preview's time scaled up
    int width = 0;
    int height = 0;
    std::string renderer; // GL renderer string
    float resolutionScale = 1.0f;
    int accumulatedFrames = 1;
};

// A screenshot: into the Capture panel's folder, named by `file` when not empty, else by
// the environment and the time; never over an existing file.
struct CaptureRequest {
    std::string file;
};

// The quit dialog's answer.
enum class QuitChoice { SaveAndQuit, Quit, Cancel };

struct UiRequests {
    std::optional<std::string> loadEnvironment; // a path or builtin:NAME
    std::optional<std::string> loadModel;       // a .gltf or .glb path
    std::optional<CaptureRequest> capture;
    std::optional<std::string> savePreset;      // lab settings as JSON
    std::optional<std::string> loadPreset;
    std::optional<std::string> exportModel;     // a copy of the loaded glTF with the tuned material
    std::optional<std::string> exportBake;      // "filament", "khronos" or "bevy": the current bake into PanelState::bakeExportPath
    std::optional<std::string> applyConvention; // conventions.hpp: rebake and set the shading as that viewer does
    bool frameScene = false;
    bool sceneChanged = false;                  // the scene kind changed: frame it
    bool countingSetup = false;                 // the counting strip's one-click setup (frame/settings.hpp)
    bool startStudy = false;                    // a quick bench sweep on the current environment and scene
    bool stopStudy = false;
    bool startAutoQuality = false;              // measure the auto candidates on the current environment and scene
    bool applyAutoQuality = false;              // bake and shade with the auto choice
    bool resetCamera = false;                   // default orientation and field of view, then frame the scene
    std::optional<CameraAxisView> axisView;     // front, side or top
    std::optional<QuitChoice> quit;             // from the quit dialog
};

struct CaptureSettings {
    char directory[1024] = ""; // the app sets the working directory at start
    char file[256] = "";       // empty: a name from the environment and the time
};

// Asked when quitting would lose settings changed since they were last saved or loaded.
struct QuitDialogState {
    bool open = false;
};

// The 3D view's rectangle in window pixels (y down).
struct ViewRect {
    float x0 = 0.0f, y0 = 0.0f, x1 = 0.0f, y1 = 0.0f;
};

// Background work the app reports to the panels: an environment loading or a bake running.
struct Activity {
    std::string text; // "" when idle
    float progress = 0.0f;
};

// The reference and the numbers of the error view, as the app last measured them.
struct CompareState {
    ReferenceStatus reference;
    ErrorReport error;
};

// The auto quality mode's choice as the Study panel shows it (lab/auto_quality.hpp).
struct AutoQualityState {
    float targetSteps = 20.0f;     // 99th-percentile display error, 8-bit steps after tone mapping (kDefaultAutoTargetSteps in lab/auto_quality.hpp says why 20)
    bool running = false;          // measuring its candidates (the StudyState's progress and chart follow it)
    bool haveChoice = false;
    bool applied = false;          // the choice is what the view bakes and shades with
    bool meetsTarget = false;
    std::string chosen;            // the settings in words
    std::string numbers;           // its cost and error
    std::vector<std::string> presets; // the fixed presets measured beside it, one line each
    std::vector<std::string> reasons;
};

// The Study panel's view of the bench sweep the app runs: progress and the chart so far.
struct StudyState {
    bool running = false;
    float progress = 0.0f;
    std::string activity;
    StatusLine status;
    std::vector<ParetoChart> charts;
    bool chartOpen = true; // the chart's window; closing it leaves the sweep running
    AutoQualityState autoQuality;
    float chartWindow[4] = {}; // the chart window's x, y, width, height as last drawn (pixels)
};

struct PanelState {
    EnvironmentCatalog catalog;
    StatusLine environmentStatus;
    StatusLine bakeStatus;
    StatusLine sceneStatus;
    StatusLine captureStatus;
    StatusLine presetStatus;
    CaptureSettings capture;
    Activity activity;
    CompareState compare;
    std::string convention; // the convention preset last applied ("" = none)
    StudyState study;
    char environmentPath[512] = "";
    char modelPath[512] = "";
    char presetPath[512] = "iblab-preset.json";
    char exportPath[512] = "iblab-export.glb";
    char bakeExportPath[512] = "iblab-ibl"; // the directory of the Environment panel's Export
    int bakeExportFormat = 0;               // index into filament, khronos, bevy
    bool showPanels = true;
    float panelWidth = 420.0f; // the control window is docked at the left; the view takes the rest
    float preferredPanelWidth = 420.0f; // the width the user chose, shown where the window allows
    ViewRect viewRect;
    QuitDialogState quitDialog;
    bool unsavedChanges = false; // settings differ from the last saved or loaded preset
    bool helpOpen = false;       // the Help window (F1)
    float hintHeight = 0.0f;     // of the hint as drawn (its space stays after it goes)
    bool firstRunHint = false;   // the panel's first line says where to start
};

void drawEnvironmentPanel(EnvironmentSettings& settings, PanelState& state, UiRequests& requests);
void drawToneMapPanel(ToneMapSettings& settings);
void drawCameraPanel(CameraSettings& settings, UiRequests& requests);
// "Quit iblab?" with Save preset and quit / Quit without saving / Cancel, while
// state.quitDialog.open; the answer goes to requests.quit.
void drawQuitDialog(PanelState& state, UiRequests& requests);
void drawMaterialPanel(MaterialSettings& settings, const SceneSettings& scene);
// exactCountForced: the scene keeps exactly N samples whatever the freeze checkbox says (the
// counting strip), so the checkbox shows on and cannot be cleared.
// `reference`: the status of the reference the frame shows (the reference method's progress).
void drawSamplingPanel(SamplingSettings& settings, bool exactCountForced, const ReferenceStatus& reference);
// The convention presets (LearnOpenGL, Filament, glTF Sample Viewer, iblab) and what each chose.
void drawConventionPanel(PanelState& state, UiRequests& requests);
// The error view's and the split view's controls, the reference's progress and the numbers.
// sceneMinRoughness: the smoothest surface shown, if known; below the reference's resolved
// roughness the panel warns that the heatmap is not the method's error there.
void drawComparePanel(ViewSettings& view, const SamplingSettings& frameSampling, const CompareState& state,
                      std::optional<float> sceneMinRoughness = std::nullopt);
void drawScenePanel(SceneSettings& settings, ShadingMethod method, PanelState& state, UiRequests& requests);
void drawViewPanel(ViewSettings& settings);
void drawPresetPanel(PanelState& state, UiRequests& requests);
void drawCapturePanel(PanelState& state, UiRequests& requests);
// Starts and stops the quick sweep; its chart is drawn live in a window of its own.
void drawStudyPanel(PanelState& state, UiRequests& requests);
void drawStudyChartWindow(StudyState& study);

// The full control window with all of the above, docked at the left.
void drawControlWindow(FrameSettings& settings, PanelState& state, const FrameStats& stats, UiRequests& requests);

} // namespace iblab::ui
