// Coder vignettes, social engagement (issue 27 part 3; docs/coder-vignettes.md): the degenerate robots of the issue,
// children who ignore or glance at a chattering partner, building one zoo, discussing what to do next, following
// and commenting, sharing items, looking on, parallel play, and their child–robot variants.
//
// Places (sandtray frame, m): the purple child plays near y = −0.27 (its edge is y = −0.335), the yellow child or
// the robot near y = −0.07 (its edge is y = 0); a shared scene lies in the middle, y = −0.17.

#include <array>
#include <string_view>
#include <utility>
#include <vector>

#include "vignette.hpp"

namespace freeplay::agents::vignette {
namespace {

using enum SocialEngagement;
using enum TaskEngagement;
using enum SocialAttitude;
using enum Utterance;
using enum sim::PaletteColour;

const Vec2 kPurpleArea{0.18, -0.27};  // where the purple child plays on its own
const Vec2 kSecondArea{0.42, -0.07};  // where the yellow child or the robot plays on its own
const Vec2 kScene{0.30, -0.17};       // a shared scene in the middle of the tray

/// `a` (bottom) and `b` (top) build one zoo in the middle: in each 6-s turn `a` places an animal and `b` places one
/// beside it 3 s later, each watching the other's move, and they talk about it (a proposal or comment, an answer).
void build_zoo_together(Player& a, Player& b, double from, double until) {
  static const std::array<std::string_view, 3> a_animals = {"lion", "zebra", "elephant"};
  static const std::array<std::string_view, 3> b_animals = {"giraffe", "hippo", "crocodile"};
  std::size_t k = 0;
  for (double t = from; t < until - 5.0; t += 6.0, ++k) {
    const double dx = -0.05 + 0.025 * static_cast<double>(k % 5);
    a.say(k % 2 == 0 ? Proposal : Comment, 1.5).at(t);  // "the lion goes here" / "and now the zebra"
    a.drag(a_animals[k % 3], {0.10 + 0.1 * static_cast<double>(k % 4), -0.30}, kScene + Vec2{dx, -0.02}).at(t + 1.0);
    b.watch_partner(1.8).at(t + 1.0);
    b.say(k % 2 == 0 ? Comment : Proposal, 1.2).at(t + 3.0);  // "yes, and the giraffe next to it"
    b.drag(b_animals[k % 3], {0.50 - 0.1 * static_cast<double>(k % 4), -0.04}, kScene + Vec2{dx + 0.02, 0.02}).at(t + 4.0);
    a.watch_partner(1.8).at(t + 4.0);
  }
}

/// `a` and `b` stop touching the screen and discuss what to do next: turns of 2 s every 3 s, the listener looking
/// at the speaker.
void discuss(Player& a, Player& b, double from, double until) {
  static const std::array<Utterance, 4> turns = {Proposal, Question, Comment, Proposal};
  Player* speaker = &a;
  Player* listener = &b;
  std::size_t k = 0;
  for (double t = from; t < until - 2.0; t += 3.0, ++k) {
    speaker->say(turns[k % turns.size()], 2.0).at(t);
    listener->look_at_partner(2.5).at(t);
    std::swap(speaker, listener);
  }
}

/// `child` (bottom) plays with its own animals, or from `imitate_from` on draws water like the partner does, and in
/// each 6-s turn watches the partner's drawing for 2 s and says something about it; `partner` (top) draws a river
/// on its side and, when `glances_back`, glances up at each remark.
void follow_and_comment(Player& child, Player& partner, double from, double until, double imitate_from,
                        bool glances_back) {
  std::size_t k = 0;
  for (double t = from; t < until - 5.5; t += 6.0, ++k) {
    if (t < imitate_from) {
      child.drag(k % 2 == 0 ? "lion" : "zebra", kPurpleArea, kPurpleArea + Vec2{0.04, 0.01}).at(t);
    } else {
      child.draw(Blue, kPurpleArea + Vec2{-0.04, 0.0}, kPurpleArea + Vec2{0.04, 0.01}, 1.8).at(t);
    }
    child.watch_partner(2.0).at(t + 2.0);
    child.say(k % 2 == 0 ? Comment : Question, 1.2).at(t + 4.2);  // "nice river!" / "is that a lake?"
    if (glances_back) partner.look_at_partner(0.6).at(t + 4.8);
  }
  draw_strokes(partner, Blue, kSecondArea, from + 1.0, until, 4.0, 2.5);
}

/// `giver` (bottom) gives `taker` (top) one of its items every 6 s: drags it over to the taker's side and says so;
/// the taker glances up, thanks it in words when `thanks`, and takes the item into its own play; between, both play
/// on their own.
void offer_items(Player& giver, Player& taker, double from, double until, bool thanks) {
  static const std::array<std::string_view, 5> gifts = {"zebra", "elephant", "lion", "ball", "caravan"};
  const Vec2 handed_over{0.32, -0.13};
  std::size_t k = 0;
  for (double t = from; t < until - 5.5; t += 6.0, ++k) {
    const std::string_view gift = gifts[k % gifts.size()];
    giver.drag(gift, kPurpleArea, handed_over).at(t);
    giver.say(Comment, 1.4).at(t + 1.6);  // "you can have the zebra"
    taker.look_at_partner(0.8).at(t + 1.8);
    if (thanks) taker.say(Comment, 1.0).at(t + 2.8);  // "thank you!"
    taker.drag(gift, handed_over, kSecondArea + Vec2{0.02 * static_cast<double>(k % 3), 0.0}).at(t + 3.6);
    giver.drag("girl", kPurpleArea + Vec2{-0.05, 0.0}, kPurpleArea + Vec2{-0.02, 0.02}).at(t + 4.0);
    taker.drag("giraffe", kSecondArea + Vec2{-0.06, 0.0}, kSecondArea + Vec2{-0.03, -0.01}).at(t + 0.2);
  }
}

Vignette robot_says_wow_on_a_timer() {
  return {"RobotSaysWowOnATimerWhileChildPlaysAlone",
          "a robot that never plays looks at the child every 4 s and says 'Wow!' every 15 s; the child arranges "
          "its animals and draws grass alone, glancing up at every second 'Wow!'",
          sentences({scheme::kSolitary, scheme::kGlance}),
          true, 90.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 2.0, 88.0);
            s.purple().draw(Green, {0.35, -0.30}, {0.45, -0.28}).at({20.5, 52.5});
            s.purple().look_at_partner(0.8).at({6.0, 36.0, 66.0});
            s.robot().look_at_partner(1.0).every(4.0, 1.0, 90.0);
            s.robot().say(Comment, 0.6).every(15.0, 5.0, 90.0);  // "Wow!"
          },
          {mostly(kPurple, Solitary, 10, 90), never(kPurple, Associative, 10, 90),
           never(kPurple, Cooperative, 10, 90), mostly(kPurple, GoalOriented, 10, 90)}};
}

Vignette timetable_mover_robot() {
  return {"TimetableMoverRobotWhileChildPlaysOnItsOwn",
          "a robot drags its animals onto the child's side next to the child's animals every 7 s and says 'Look!' "
          "every 21 s; the child keeps arranging its own animals, looks at the moved animal and up at the robot now "
          "and then",
          sentences({scheme::kParallel, scheme::kNotMe, scheme::kGlance}),
          true, 90.0,
          [](Script& s) {
            static const std::array<std::string_view, 4> items = {"giraffe", "hippo", "crocodile", "boy"};
            std::size_t k = 0;
            for (double t = 3.0; t < 88.0; t += 7.0, ++k) {
              s.robot().drag(items[k % items.size()], {0.45, -0.20}, {0.26 + 0.02 * static_cast<double>(k % 3), -0.25},
                             2.0).at(t);
            }
            s.robot().say(Comment, 0.6).at({10.0, 31.0, 52.0, 73.0});  // "Look!"
            s.robot().look_at_partner(1.0).at({10.0, 31.0, 52.0, 73.0});
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 2.0, 88.0);
            s.purple().watch_partner(1.0).at({10.5, 31.5, 52.5, 73.5});
            s.purple().look_at_partner(0.8).at({12.0, 54.0});
          },
          {mostly_one_of(kPurple, {Solitary, Parallel}, 10, 90, 0.9), never(kPurple, Cooperative, 10, 90),
           never(kPurple, Associative, 10, 90)}};
}

Vignette child_ignores_chattering_robot() {
  return {"ChildIgnoresAChatteringRobot",
          "a robot that never plays talks to the child every 5 s (comments, questions, proposals), looking at it; the "
          "child never looks up nor answers and plays alone",
          sentences({scheme::kSolitary}),
          true, 80.0,
          [](Script& s) {
            static const std::array<Utterance, 3> chatter = {Comment, Question, Proposal};
            std::size_t k = 0;
            for (double t = 3.0; t < 78.0; t += 5.0, ++k) s.robot().say(chatter[k % chatter.size()], 1.5).at(t);
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 2.0, 78.0, 3.5);
            s.purple().draw(Blue, {0.40, -0.25}, {0.50, -0.24}).at({30.0, 60.0});
          },
          {mostly(kPurple, Solitary, 10, 80), never(kPurple, Associative, 10, 80),
           never(kPurple, Cooperative, 10, 80)}};
}

Vignette child_glances_back_at_robot_comments() {
  return {"ChildGlancesBackAtEachRobotCommentButPlaysAlone",
          "a robot that never plays comments every 8 s, looking at the child; the child glances up 0.6 s after each "
          "comment and goes straight back to its own animals, without a word",
          sentences({scheme::kGlance, scheme::kSolitary}),
          true, 80.0,
          [](Script& s) {
            s.robot().say(Comment, 1.0).every(8.0, 4.0, 80.0);
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 79.0);
            s.purple().look_at_partner(0.8).every(8.0, 4.6, 80.0);
          },
          {mostly(kPurple, Solitary, 10, 80), never(kPurple, Associative, 10, 80),
           never(kPurple, Cooperative, 10, 80)}};
}

Vignette child_answers_robot_remarks() {
  return {"ChildAnswersTheRobotsRemarksAboutItsPlay",
          "a robot that never plays remarks on the child's scene every 8 s ('is the lion hungry?'); the child "
          "answers each in words, looking up ('yes, he eats the zebra!'), and goes on arranging its animals",
          sentences({scheme::kAssociative, scheme::kGlance}),
          true, 80.0,
          [](Script& s) {
            s.robot().say(Question, 1.2).every(8.0, 4.0, 80.0);
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 79.0);
            s.purple().say(Comment, 1.5).every(8.0, 5.6, 80.0);
          },
          {mostly(kPurple, Associative, 12, 80), never(kPurple, Cooperative, 12, 80)}};
}

Vignette two_children_build_one_zoo() {
  return {"TwoChildrenBuildOneZoo",
          "two children take turns placing animals side by side in one zoo in the middle, each watching the other's "
          "move and talking about where each animal goes",
          sentences({scheme::kCooperative}),
          false, 90.0,
          [](Script& s) { build_zoo_together(s.purple(), s.yellow(), 2.0, 90.0); },
          {mostly(kPurple, Cooperative, 15, 90), mostly(kYellow, Cooperative, 15, 90),
           mostly(kPurple, GoalOriented, 15, 90), mostly(kYellow, GoalOriented, 15, 90)}};
}

Vignette two_children_discuss_what_to_do_next() {
  return {"TwoChildrenDiscussWhatToDoNext",
          "two children play apart for 20 s, then stop and discuss what to do next for 24 s (proposals, questions, "
          "answers, looking at each other, no touches), then build one zoo together",
          sentences({scheme::kDiscussing, scheme::kCooperative, scheme::kGoalOriented}),
          false, 70.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 19.0);
            arrange(s.yellow(), {"giraffe", "hippo"}, kSecondArea, 2.0, 19.0);
            discuss(s.purple(), s.yellow(), 20.0, 44.0);
            build_zoo_together(s.purple(), s.yellow(), 44.0, 70.0);
          },
          {mostly(kPurple, Cooperative, 24, 44), mostly(kYellow, Cooperative, 24, 44),
           mostly(kPurple, Cooperative, 50, 70), mostly(kYellow, Cooperative, 50, 70),
           mostly(kPurple, GoalOriented, 24, 44)}};
}

Vignette child_follows_partner_and_comments() {
  return {"ChildFollowsThePartnersDrawingAndCommentsOnIt",
          "the yellow child draws a river on its side; the purple child plays with its own animals, watches the "
          "river grow, says something about it every 6 s and from 40 s draws water of its own; yellow only glances "
          "up at the remarks",
          sentences({scheme::kAssociative, scheme::kGlance}),
          false, 80.0,
          [](Script& s) { follow_and_comment(s.purple(), s.yellow(), 1.0, 80.0, 40.0, true); },
          {mostly(kPurple, Associative, 15, 80), never(kPurple, Cooperative, 15, 80),
           never(kYellow, Cooperative, 15, 80), never(kYellow, Associative, 15, 80)}};
}

Vignette child_offers_items() {
  return {"ChildOffersItemsToThePartner",
          "the purple child hands the yellow child one of its animals every 6 s ('you can have the zebra'); yellow "
          "glances up and takes each into its own play, without a word; otherwise both play on their own",
          sentences({scheme::kAssociative, scheme::kAdversarial}),
          false, 70.0,
          [](Script& s) { offer_items(s.purple(), s.yellow(), 4.0, 70.0, false); },
          {mostly(kPurple, Associative, 12, 70), never(kPurple, Cooperative, 12, 70),
           never(kYellow, Cooperative, 12, 70), never(kYellow, Adversarial, 0, 70)}};
}

Vignette one_child_onlooking() {
  return {"OneChildWatchesTheOtherDraw",
          "the yellow child draws grass and moves a giraffe on its side; from 10 s the purple child stops and keeps "
          "its eyes on yellow's finger, without touching or speaking",
          sentences({scheme::kOnlooker, scheme::kSolitary}),
          false, 70.0,
          [](Script& s) {
            draw_strokes(s.yellow(), Green, kSecondArea, 1.0, 69.0, 3.5, 2.5);
            arrange(s.yellow(), {"giraffe"}, kSecondArea + Vec2{-0.2, 0.0}, 3.0, 69.0, 7.0);
            arrange(s.purple(), {"lion"}, kPurpleArea, 1.0, 10.0);
            s.purple().watch_partner(60.0).at(10.0);
          },
          {mostly(kPurple, Onlooker, 16, 70), mostly(kYellow, Solitary, 16, 70),
           never(kPurple, Associative, 16, 70)}};
}

Vignette parallel_play() {
  return {"ParallelPlayWithSimilarMaterials",
          "both children arrange animals on their own sides, without a word, each glancing at the other's play now "
          "and then",
          sentences({scheme::kParallel}),
          false, 80.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 79.0);
            arrange(s.yellow(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 2.5, 79.0, 4.5);
            s.purple().watch_partner(1.2).at({17.0, 41.0, 63.0});
            s.yellow().watch_partner(1.2).at({29.0, 52.0});
          },
          {mostly(kPurple, Parallel, 10, 80), mostly(kYellow, Parallel, 10, 80), never(kPurple, Associative, 10, 80),
           never(kYellow, Associative, 10, 80), never(kPurple, Cooperative, 10, 80),
           never(kYellow, Cooperative, 10, 80)}};
}

/// The yellow child drags its animals right next to the purple child's every 5 s and says "look!" every 10 s, while
/// purple arranges its own animals; purple glances up 0.6 s after each "look!" when `purple_glances`.
void acts_next_to_purple(Script& s, bool purple_glances) {
  arrange(s.purple(), {"lion", "zebra"}, {0.20, -0.26}, 1.0, 79.0);
  static const std::array<std::string_view, 3> items = {"giraffe", "hippo", "crocodile"};
  std::size_t k = 0;
  for (double t = 3.0; t < 78.0; t += 5.0, ++k) {
    s.yellow().drag(items[k % items.size()], {0.35, -0.10}, {0.23 + 0.01 * static_cast<double>(k % 3), -0.23}).at(t);
  }
  s.yellow().say(Comment, 1.0).every(10.0, 5.0, 78.0);  // "look!"
  if (purple_glances) s.purple().look_at_partner(0.8).every(10.0, 5.6, 78.0);
}

Vignette partner_acts_near_my_item() {
  return {"PartnerKeepsActingNextToMyAnimalsWhileIIgnoreIt",
          "the yellow child drags its animals right next to the purple child's animals every 5 s and says 'look!' "
          "every 10 s; purple never looks up nor answers and keeps arranging its own animals",
          sentences({scheme::kNotMe, scheme::kParallel}),
          false, 80.0,
          [](Script& s) { acts_next_to_purple(s, false); },
          {never(kPurple, Cooperative, 10, 80), never(kPurple, Associative, 10, 80)}};
}

Vignette partner_acts_near_my_item_i_glance() {
  return {"PartnerKeepsActingNextToMyAnimalsIGlanceUpButPlayOn",
          "as before, but purple glances up at each 'look!' before going back to its own animals, without a word",
          sentences({scheme::kNotMe, scheme::kGlance, scheme::kParallel}),
          false, 80.0,
          [](Script& s) { acts_next_to_purple(s, true); },
          {never(kPurple, Cooperative, 10, 80), never(kPurple, Associative, 10, 80),
           mostly(kPurple, Parallel, 10, 80)}};
}

Vignette child_watches_robot_play() {
  return {"ChildWatchesTheRobotPlay",
          "the robot arranges animals on its side every 3.5 s; from 10 s the child stops and watches the robot's "
          "moves, without touching or speaking",
          sentences({scheme::kOnlooker}),
          true, 70.0,
          [](Script& s) {
            arrange(s.robot(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 1.0, 69.0, 3.5);
            arrange(s.purple(), {"lion"}, kPurpleArea, 1.0, 10.0);
            s.purple().watch_partner(60.0).at(10.0);
          },
          {mostly(kPurple, Onlooker, 16, 70), never(kPurple, Associative, 16, 70)}};
}

Vignette child_and_robot_in_parallel() {
  return {"ChildAndRobotPlayInParallel",
          "the child and the robot arrange animals on their own sides, without a word",
          sentences({scheme::kParallel}),
          true, 70.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 69.0);
            arrange(s.robot(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 2.0, 69.0, 5.0);
          },
          {mostly(kPurple, Parallel, 10, 70), never(kPurple, Associative, 10, 70),
           never(kPurple, Cooperative, 10, 70)}};
}

Vignette child_and_robot_build_one_scene() {
  return {"ChildAndRobotBuildOneZoo",
          "the child and the robot take turns placing animals side by side in one zoo, watching each other's move "
          "and talking about it",
          sentences({scheme::kCooperative}),
          true, 90.0,
          [](Script& s) { build_zoo_together(s.purple(), s.robot(), 2.0, 90.0); },
          {mostly(kPurple, Cooperative, 15, 90)}};
}

Vignette child_comments_on_robot_drawing() {
  return {"ChildCommentsOnTheRobotsDrawing",
          "the robot draws a river on its side and glances up at each remark; the child plays with its own animals, "
          "watches the river grow and says something about it every 6 s, from 40 s drawing water of its own",
          sentences({scheme::kAssociative}),
          true, 70.0,
          [](Script& s) { follow_and_comment(s.purple(), s.robot(), 1.0, 70.0, 40.0, true); },
          {mostly(kPurple, Associative, 15, 70), never(kPurple, Cooperative, 15, 70)}};
}

Vignette child_plays_beside_idle_robot() {
  return {"ChildPlaysAloneBesideAnIdleRobot",
          "the robot does nothing; the child arranges animals and draws",
          sentences({scheme::kSolitary}),
          true, 60.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 59.0);
            s.purple().draw(Green, {0.35, -0.30}, {0.45, -0.28}).at({18.5, 38.5});
          },
          {mostly(kPurple, Solitary, 8, 60, 0.9)}};
}

Vignette parallel_then_together() {
  return {"ParallelPlayThenBuildingTogether",
          "two children play apart for 34 s; then purple proposes a zoo, yellow agrees, and they build it together",
          sentences({scheme::kParallel, scheme::kCooperative}),
          false, 80.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 33.0);
            arrange(s.yellow(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 2.5, 33.0, 4.5);
            s.purple().say(Proposal, 2.0).at(34.0);  // "let's make a zoo together!"
            s.yellow().look_at_partner(2.5).at(34.0);
            s.yellow().say(Comment, 1.0).at(36.5);  // "yes!"
            build_zoo_together(s.purple(), s.yellow(), 38.0, 80.0);
          },
          {mostly(kPurple, Parallel, 8, 33), mostly(kYellow, Parallel, 8, 33), mostly(kPurple, Cooperative, 45, 80),
           mostly(kYellow, Cooperative, 45, 80)}};
}

Vignette talking_about_own_play() {
  return {"TalkingAboutTheirOwnPlayWithoutASharedGoal",
          "both children arrange animals on their own sides and talk to each other about what they are doing "
          "('my lion is sleeping' — 'my giraffe is eating'), each answering the other, every 4 s",
          sentences({scheme::kAssociative}),
          false, 80.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 79.0);
            arrange(s.yellow(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 3.0, 79.0);
            s.purple().say(Comment, 1.5).every(8.0, 4.8, 79.0);
            s.yellow().say(Comment, 1.5).every(8.0, 7.0, 79.0);
            s.purple().look_at_partner(1.2).every(8.0, 7.2, 79.0);
            s.yellow().look_at_partner(1.2).every(8.0, 5.0, 79.0);
          },
          {mostly(kPurple, Associative, 12, 80), mostly(kYellow, Associative, 12, 80),
           never(kPurple, Cooperative, 12, 80), never(kYellow, Cooperative, 12, 80)}};
}

Vignette passing_the_ball() {
  return {"PassingTheBallBackAndForth",
          "two children take turns flicking the ball to each other across the tray, watching it come and calling "
          "out ('catch!')",
          sentences({scheme::kCooperative, scheme::kAdversarial}),
          false, 60.0,
          [](Script& s) {
            const Vec2 purple_end{0.30, -0.27};
            const Vec2 yellow_end{0.32, -0.08};
            s.purple().drag("ball", purple_end, yellow_end, 1.2).every(6.0, 3.0, 60.0);
            s.yellow().drag("ball", yellow_end, purple_end, 1.2).every(6.0, 6.0, 60.0);
            s.purple().watch_partner(2.0).every(6.0, 5.5, 60.0);
            s.yellow().watch_partner(2.0).every(6.0, 2.5, 60.0);
            s.purple().say(Comment, 0.8).every(12.0, 2.0, 60.0);  // "catch!"
            s.yellow().say(Comment, 0.8).every(12.0, 5.0, 60.0);
          },
          {mostly(kPurple, Cooperative, 10, 60), mostly(kYellow, Cooperative, 10, 60),
           never(kPurple, Adversarial, 0, 60), never(kYellow, Adversarial, 0, 60)}};
}

Vignette river_and_animals() {
  return {"OneDrawsTheRiverTheOtherPlacesAnimalsAlongIt",
          "complementary roles: purple draws a river across the middle, stroke after stroke; yellow places animals "
          "along each new stretch of bank; they talk about where the river goes",
          sentences({scheme::kCooperative}),
          false, 80.0,
          [](Script& s) {
            static const std::array<std::string_view, 3> animals = {"crocodile", "hippo", "zebra"};
            s.purple().draw(Blue, {0.10, -0.17}, {0.14, -0.17}, 2.5).at(2.0);
            std::size_t k = 1;
            for (double t = 6.0; t < 78.0; t += 4.0, ++k) {
              const double x = 0.10 + 0.04 * static_cast<double>(k % 11);
              s.purple().stroke({x, -0.17}, {x + 0.04, -0.17}, 2.5).at(t);
            }
            k = 0;
            for (double t = 4.5; t < 78.0; t += 4.0, ++k) {
              const double x = 0.12 + 0.04 * static_cast<double>(k % 11);
              s.yellow().drag(animals[k % animals.size()], {x, -0.05}, {x, -0.14}).at(t);
              s.purple().watch_partner(1.5).at(t);
            }
            s.yellow().say(Proposal, 1.5).every(12.0, 8.0, 78.0);   // "make it go round the hippo"
            s.purple().say(Comment, 1.2).every(12.0, 10.0, 78.0);   // "ok, like this"
            s.purple().say(Question, 1.2).every(12.0, 14.0, 78.0);  // "where does the crocodile go?"
            s.yellow().say(Comment, 1.2).every(12.0, 15.5, 78.0);
          },
          {mostly(kPurple, Cooperative, 15, 80), mostly(kYellow, Cooperative, 15, 80)}};
}

Vignette child_glances_back_at_peer() {
  return {"ChildGlancesBackAtItsPeersCommentsButPlaysAlone",
          "the yellow child plays on its side and comments to purple every 7 s; purple glances up after each "
          "comment and goes back to its own animals, without a word",
          sentences({scheme::kGlance, scheme::kParallel}),
          false, 80.0,
          [](Script& s) {
            arrange(s.yellow(), {"giraffe", "hippo"}, kSecondArea, 2.0, 79.0);
            s.yellow().say(Comment, 1.2).every(7.0, 5.0, 79.0);
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 79.0);
            s.purple().look_at_partner(0.7).every(7.0, 5.6, 79.0);
          },
          {mostly(kPurple, Parallel, 10, 80), never(kPurple, Associative, 10, 80),
           never(kPurple, Cooperative, 10, 80)}};
}

Vignette child_and_robot_discuss() {
  return {"ChildAndRobotDiscussWhatToDoNext",
          "the child and the robot play apart for 18 s, then stop and discuss what to do next for 22 s (turns of "
          "proposals, questions and answers, looking at each other), then build one zoo together",
          sentences({scheme::kDiscussing, scheme::kCooperative}),
          true, 62.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 17.0);
            arrange(s.robot(), {"giraffe", "hippo"}, kSecondArea, 2.0, 17.0);
            discuss(s.purple(), s.robot(), 18.0, 40.0);
            build_zoo_together(s.purple(), s.robot(), 40.0, 62.0);
          },
          {mostly(kPurple, Cooperative, 22, 40), mostly(kPurple, Cooperative, 46, 62)}};
}

Vignette child_shares_with_robot() {
  return {"ChildSharesItemsWithTheRobot",
          "the child hands the robot one of its animals every 6 s ('this is for you'); the robot looks up, says "
          "'thank you!' and takes each into its own play; otherwise both play on their own",
          sentences({scheme::kAssociative}),
          true, 70.0,
          [](Script& s) { offer_items(s.purple(), s.robot(), 4.0, 70.0, true); },
          {mostly(kPurple, Associative, 12, 70), never(kPurple, Cooperative, 12, 70)}};
}

Vignette peer_answers_in_words() {
  return {"ChildAnswersAPeerTalkingAboutThePlayInWords",
          "the purple child arranges its animals and talks to the yellow child about the play every 6 s; yellow "
          "draws on its side and answers in a word every third remark, looking up ('yes!'): each keeps to its own "
          "scene, both talk about the play",
          sentences({scheme::kAssociative, scheme::kResponds}),
          false, 80.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 79.0);
            s.purple().say(Comment, 1.2).every(6.0, 3.0, 80.0);
            draw_strokes(s.yellow(), Blue, kSecondArea, 1.0, 80.0, 4.0, 2.5);
            s.yellow().say(Comment, 0.8).every(18.0, 4.6, 80.0);
          },
          {mostly(kPurple, Associative, 15, 80), mostly(kYellow, Associative, 15, 80),
           never(kYellow, Cooperative, 15, 80)}};
}

Vignette onlooker_joins_the_play() {
  return {"ChildWatchesThenJoinsThePartnersZoo",
          "the yellow child builds a zoo in the middle; from 6 s the purple child stops and watches it; at 30 s purple "
          "joins it — brings its lion, then its zebra beside the animals yellow just placed, and from 37 s they build "
          "it together in turns, talking about it (entry by watching first: Corsaro 1979); the cooperation is coded from purple's "
          "joining move, not after a stretch of play alongside",
          sentences({scheme::kOnlooker, scheme::kCooperative}),
          false, 90.0,
          [](Script& s) {
            arrange(s.yellow(), {"giraffe", "hippo", "crocodile"}, kScene + Vec2{0.03, 0.02}, 1.0, 29.0, 4.0);
            arrange(s.purple(), {"lion"}, kPurpleArea, 1.0, 6.0);
            s.purple().watch_partner(23.5).at(6.0);
            // Purple joins without a word first: its animals go beside the ones yellow just placed.
            s.yellow().drag("boy", {0.50, -0.04}, kScene + Vec2{0.06, 0.02}).at(29.5);
            s.purple().drag("lion", kPurpleArea, kScene + Vec2{0.04, 0.0}).at(31.0);
            s.yellow().drag("girl", {0.50, -0.04}, kScene + Vec2{0.02, 0.03}).at(33.0);
            s.purple().drag("zebra", kPurpleArea, kScene + Vec2{0.0, 0.02}).at(34.5);
            s.yellow().watch_partner(1.5).at(34.5);
            build_zoo_together(s.purple(), s.yellow(), 37.0, 90.0);
          },
          {mostly(kPurple, Onlooker, 12, 30), mostly(kPurple, Cooperative, 32, 90), never(kPurple, Parallel, 30, 90),
           never(kPurple, Solitary, 30, 90)}};
}

Vignette both_pause_their_parallel_play() {
  return {"BothChildrenPauseTheirParallelPlay",
          "both children arrange animals on their own sides, glancing at each other's play now and then; from 40 s "
          "to 100 s neither touches the screen (both look around the room), then both go on as before; a coder "
          "does not code the shared pause as solitary play",
          sentences({scheme::kParallel, scheme::kNoUnoccupied}),
          false, 140.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 1.0, 39.0);
            arrange(s.yellow(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 2.5, 39.0, 4.5);
            s.purple().watch_partner(1.2).at({17.0, 31.0});
            s.yellow().watch_partner(1.2).at({24.0, 35.0});
            s.purple().look_away(5.0).every(6.0, 40.0, 100.0);
            s.yellow().look_away(5.0).every(6.0, 41.0, 100.0);
            arrange(s.purple(), {"lion", "zebra", "elephant"}, kPurpleArea, 101.0, 139.0);
            arrange(s.yellow(), {"giraffe", "hippo", "crocodile"}, kSecondArea, 102.0, 139.0, 4.5);
          },
          {mostly(kPurple, Parallel, 10, 140), mostly(kYellow, Parallel, 10, 140), never(kPurple, Solitary, 40, 140),
           never(kYellow, Solitary, 40, 140)}};
}

std::vector<Vignette> social_vignettes() {
  return {robot_says_wow_on_a_timer(),
          timetable_mover_robot(),
          child_ignores_chattering_robot(),
          child_glances_back_at_robot_comments(),
          child_answers_robot_remarks(),
          two_children_build_one_zoo(),
          two_children_discuss_what_to_do_next(),
          child_follows_partner_and_comments(),
          child_offers_items(),
          one_child_onlooking(),
          parallel_play(),
          partner_acts_near_my_item(),
          partner_acts_near_my_item_i_glance(),
          child_watches_robot_play(),
          child_and_robot_in_parallel(),
          child_and_robot_build_one_scene(),
          child_comments_on_robot_drawing(),
          child_plays_beside_idle_robot(),
          parallel_then_together(),
          talking_about_own_play(),
          passing_the_ball(),
          river_and_animals(),
          child_glances_back_at_peer(),
          child_and_robot_discuss(),
          child_shares_with_robot(),
          peer_answers_in_words(),
          onlooker_joins_the_play(),
          both_pause_their_parallel_play()};
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(SocialEngagement, CoderVignette, ::testing::ValuesIn(social_vignettes()), vignette_name);

}  // namespace freeplay::agents::vignette
