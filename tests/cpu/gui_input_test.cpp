// The GUI's input queue hands events to Dear ImGui a frame at a time without losing a tap,
// and the script language parses what docs/gui-scripts.md describes and refuses the rest.
#include <GLFW/glfw3.h>
#include <gtest/gtest.h>
#include <imgui.h>

#include "gui_input.hpp"
#include "gui_script.hpp"

namespace iblab::app {
namespace {

// A Dear ImGui context for the IO struct alone (no frame is drawn).
class InputQueueTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        context_ = ImGui::CreateContext();
        mapGlfwKeys(ImGui::GetIO());
    }
    void TearDown() override { ImGui::DestroyContext(context_); }
    ImGuiIO& io() { return ImGui::GetIO(); }
    static InputEvent key(int code, bool pressed) { return {.type = InputEvent::Type::Key, .code = code, .pressed = pressed}; }
    static InputEvent button(int code, bool pressed) { return {.type = InputEvent::Type::MouseButton, .code = code, .pressed = pressed}; }
    static InputEvent move(double x, double y) { return {.type = InputEvent::Type::CursorMoved, .x = x, .y = y}; }
    ImGuiContext* context_ = nullptr;
};

TEST_F(InputQueueTest, ATapWithinOneFrameIsSeenDownThenUp)
{
    InputQueue queue;
    queue.push(key(GLFW_KEY_KP_ADD, true));
    queue.push(key(GLFW_KEY_KP_ADD, false));
    queue.applyFrame(io());
    EXPECT_TRUE(io().KeysDown[GLFW_KEY_KP_ADD]);
    EXPECT_EQ(queue.size(), 1u);
    queue.applyFrame(io());
    EXPECT_FALSE(io().KeysDown[GLFW_KEY_KP_ADD]);
    EXPECT_TRUE(queue.empty());
}

TEST_F(InputQueueTest, AClickLandsWhereItWasMade)
{
    InputQueue queue;
    queue.push(move(10, 20));
    queue.push(button(0, true));
    queue.push(button(0, false));
    queue.push(move(300, 400));
    queue.applyFrame(io());
    EXPECT_EQ(io().MousePos.x, 10.0f);
    EXPECT_TRUE(io().MouseDown[0]);
    queue.applyFrame(io());
    EXPECT_FALSE(io().MouseDown[0]);
    EXPECT_EQ(io().MousePos.x, 10.0f) << "the move after the release waits for the frame after it";
    queue.applyFrame(io());
    EXPECT_EQ(io().MousePos.x, 300.0f);
}

TEST_F(InputQueueTest, ModifiersFollowTheirKeysAndTextWaitsForKeys)
{
    InputQueue queue;
    queue.push(key(GLFW_KEY_LEFT_CONTROL, true));
    queue.push(key(GLFW_KEY_A, true));
    queue.push({.type = InputEvent::Type::Text, .codepoint = 'x'});
    queue.applyFrame(io());
    EXPECT_TRUE(io().KeyCtrl);
    EXPECT_TRUE(io().KeysDown[GLFW_KEY_A]);
    EXPECT_EQ(io().InputQueueCharacters.Size, 0) << "text after a key change waits: Ctrl+A must select before the typing replaces";
    queue.applyFrame(io());
    EXPECT_EQ(io().InputQueueCharacters.Size, 1);
}

TEST_F(InputQueueTest, DropsCloseAndWheelReachTheApp)
{
    InputQueue queue;
    queue.push({.type = InputEvent::Type::Scroll, .y = 1.0});
    queue.push({.type = InputEvent::Type::Scroll, .y = 2.0});
    queue.push({.type = InputEvent::Type::Drop, .paths = {"a.exr", "b.glb"}});
    queue.push({.type = InputEvent::Type::CloseRequest});
    const FrameRequests requests = queue.applyFrame(io());
    EXPECT_EQ(io().MouseWheel, 3.0f);
    EXPECT_EQ(requests.dropped, (std::vector<std::string>{"a.exr", "b.glb"}));
    EXPECT_TRUE(requests.closeRequested);
}

TEST(GuiScript, ParsesStepsQuotesAndComments)
{
    const std::vector<ScriptStep> steps = parseGuiScript("# a comment\n"
                                                         "select \"Scene/Scene\" grid   # trailing comment\n"
                                                         "\n"
                                                         "expect /settings/scene/kind == \"grid\"\n"
                                                         "type \"say \\\"hi\\\"\"\n");
    ASSERT_EQ(steps.size(), 3u);
    EXPECT_EQ(steps[0].line, 2);
    EXPECT_EQ(steps[0].command, "select");
    EXPECT_EQ(steps[0].args, (std::vector<std::string>{"Scene/Scene", "grid"}));
    EXPECT_EQ(steps[1].args[2], "grid");
    EXPECT_EQ(steps[2].args[0], "say \"hi\"");
}

TEST(GuiScript, RefusesWhatItCannotRunNamingTheLine)
{
    auto refused = [](const std::string& text) {
        try {
            parseGuiScript(text);
        } catch (const std::runtime_error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    EXPECT_NE(refused("frames 1\nfly away\n").find("line 2: unknown command \"fly\""), std::string::npos);
    EXPECT_NE(refused("click\n").find("line 1: click takes 1 to 3 arguments, got 0"), std::string::npos);
    EXPECT_NE(refused("type \"open\n").find("unterminated quote"), std::string::npos);
    EXPECT_NE(refused("key ctrl+nothing\n").find("unknown key"), std::string::npos);
    EXPECT_NE(refused("drop ${IBLAB_SURELY_UNSET_VARIABLE}/x.exr\n").find("IBLAB_SURELY_UNSET_VARIABLE is not set"), std::string::npos);
}

TEST(GuiScript, ExpandsEnvironmentVariables)
{
    setenv("IBLAB_SCRIPT_TEST_DIR", "/data", 1);
    const std::vector<ScriptStep> steps = parseGuiScript("drop ${IBLAB_SCRIPT_TEST_DIR}/m.glb\n");
    EXPECT_EQ(steps[0].args[0], "/data/m.glb");
}

TEST(GuiScript, KeyChords)
{
    const auto quit = parseKeyChord("ctrl+q");
    ASSERT_TRUE(quit);
    EXPECT_EQ(quit->key, GLFW_KEY_Q);
    EXPECT_EQ(quit->modifiers, std::vector<int>{GLFW_KEY_LEFT_CONTROL});
    EXPECT_EQ(parseKeyChord("Escape")->key, GLFW_KEY_ESCAPE);
    EXPECT_EQ(parseKeyChord("F12")->key, GLFW_KEY_F12);
    EXPECT_EQ(parseKeyChord("plus")->key, GLFW_KEY_KP_ADD);
    EXPECT_EQ(parseKeyChord("ctrl+shift+s")->modifiers.size(), 2u);
    EXPECT_FALSE(parseKeyChord("hyper+x"));
}

} // namespace
} // namespace iblab::app
