// Coder vignettes, task engagement and social attitude (issue 27 part 3; docs/coder-vignettes.md): drawing the
// landscape and placing animals in habitats, scribbles and silly taps, asking the experimenter, a child who has
// stopped playing, grabbing the other's item, a protest after losing it, bossy proposals, friendly help.
//
// Places (sandtray frame, m): the purple child plays near y = −0.27 (its edge is y = −0.335), the yellow child or
// the robot near y = −0.07 (its edge is y = 0).

#include <array>
#include <cmath>
#include <string_view>
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

/// `owner` plays with the lion in `owner_area` until 17.5 s; `taker`, playing with its own animals in `taker_area`,
/// watches, then at 19 s drags the lion away to its side without a word and plays with it. The owner looks up; when
/// `protests`, it protests three times ("hey, that's mine!", "give it back!") and sulks until 32 s, else it goes on
/// with another animal.
void snatch_the_lion(Player& owner, Vec2 owner_area, Player& taker, Vec2 taker_area, bool protests, double until) {
  arrange(owner, {"lion"}, owner_area, 1.0, 17.0, 3.0);
  arrange(taker, {"zebra", "girl"}, taker_area, 1.0, 16.0);
  taker.watch_partner(2.0).at(17.0);
  taker.drag("lion", owner_area, taker_area, 1.5).at(19.0);
  arrange(taker, {"lion"}, taker_area, 23.0, until);
  owner.look_at_partner(1.5).at(20.5);
  if (protests) {
    owner.say(Protest, 1.5).at({21.0, 24.0, 27.0});
    owner.watch_partner(3.5).at(28.5);
    arrange(owner, {"giraffe", "hippo"}, owner_area, 32.0, until);
  } else {
    arrange(owner, {"giraffe", "hippo"}, owner_area, 23.0, until);
  }
}

Vignette landscape_drawing() {
  return {"DrawingTheLandscapeInLandscapeColours",
          "beside an idle robot, the child draws grass in green (a stroke of 2.5 s every 3.5 s), then water in blue, "
          "picking the colour before each stroke",
          sentences({scheme::kGoalOriented}),
          true, 60.0,
          [](Script& s) {
            draw_strokes(s.purple(), Green, {0.20, -0.25}, 1.0, 30.0, 3.5, 2.5);
            draw_strokes(s.purple(), Blue, {0.40, -0.20}, 30.5, 60.0, 3.5, 2.5);
          },
          {mostly(kPurple, GoalOriented, 8, 60, 0.8)}};
}

Vignette landscape_after_one_pick() {
  return {"ALandscapeDrawnInManyStrokesAfterOneColourPick",
          "the child picks green once and draws a meadow in 16 strokes without touching the palette again (the "
          "colour stays selected in the real game)",
          sentences({scheme::kGoalOriented}),
          true, 60.0,
          [](Script& s) {
            s.purple().draw(Green, {0.10, -0.25}, {0.16, -0.25}, 2.5).at(2.0);
            std::size_t k = 1;
            for (double t = 5.5; t < 58.0; t += 3.5, ++k) {
              const double x = 0.10 + 0.03 * static_cast<double>(k % 12);
              const double y = -0.25 + 0.01 * static_cast<double>(k % 3);
              s.purple().stroke({x, y}, {x + 0.06, y}, 2.5).at(t);
            }
          },
          {mostly(kPurple, GoalOriented, 10, 60, 0.8)}};
}

Vignette animals_in_habitats() {
  return {"PlacingAnimalsInTheirHabitats",
          "the child draws a blue pond and a green meadow, then drags the crocodile and the hippo into the pond and "
          "the zebra, the giraffe and the elephant onto the meadow, one every 4 s",
          sentences({scheme::kGoalOriented}),
          true, 60.0,
          [](Script& s) {
            s.purple().draw(Blue, {0.42, -0.20}, {0.50, -0.20}, 2.5).at(1.0);
            s.purple().draw(Green, {0.12, -0.25}, {0.22, -0.25}, 2.5).at(4.5);
            static const std::array<std::string_view, 5> animals = {"crocodile", "zebra", "hippo", "giraffe",
                                                                    "elephant"};
            std::size_t k = 0;
            for (double t = 8.0; t < 58.0; t += 4.0, ++k) {
              const std::string_view animal = animals[k % animals.size()];
              const bool water = animal == "crocodile" || animal == "hippo";
              const Vec2 home = water ? Vec2{0.46, -0.20} : Vec2{0.17, -0.25};
              s.purple().drag(animal, {0.30, -0.31}, home + Vec2{0.01 * static_cast<double>(k % 3), 0.0}).at(t);
            }
          },
          {mostly(kPurple, GoalOriented, 8, 60, 0.8)}};
}

Vignette scribbles() {
  return {"ScribblingInNonLandscapeColours",
          "the child keeps changing between red, black, purple and orange and makes short zigzags (0.8 s) every "
          "2.5 s all over its side",
          sentences({scheme::kAimless}),
          true, 60.0,
          [](Script& s) {
            static const std::array<sim::PaletteColour, 4> colours = {Red, Black, Purple, Orange};
            std::size_t k = 0;
            for (double t = 1.0; t < 59.0; t += 2.5, ++k) {
              const double x = 0.08 + 0.11 * static_cast<double>(k % 5);
              s.purple().draw(colours[k % colours.size()], {x, -0.22}, {x + 0.03, -0.26}, 0.8).at(t);
            }
          },
          {mostly(kPurple, Aimless, 10, 60)}};
}

Vignette silly_taps() {
  return {"SillyTapsAllOverTheScreen",
          "the child taps the empty tray here and there, every 0.7 s, with no colour and no item",
          sentences({scheme::kAimless}),
          true, 60.0,
          [](Script& s) {
            std::size_t k = 0;
            for (double t = 2.0; t < 58.0; t += 0.7, ++k) {
              const double u = static_cast<double>(k);
              s.purple().tap({0.05 + std::fmod(0.37 * u, 0.5), -0.05 - std::fmod(0.23 * u, 0.25)}).at(t);
            }
          },
          {mostly(kPurple, Aimless, 10, 58)}};
}

Vignette asks_experimenter() {
  return {"AskingTheExperimenter",
          "the child plays for 20 s, then turns to the experimenter for 15 s, looking at her and asking twice ('can "
          "I draw too?', 'is this right?'), without playing; then plays again",
          sentences({scheme::kAdultSeeking, scheme::kGoalOriented}),
          true, 75.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 19.0);
            s.purple().look_at_experimenter(2.0).at({20.0, 25.0, 30.0});
            s.purple().ask_experimenter(Question, 2.0).at({21.0, 31.0});
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 37.0, 75.0);
          },
          {mostly(kPurple, AdultSeeking, 21, 35), mostly(kPurple, GoalOriented, 47, 75)}};
}

Vignette stopped_playing() {
  return {"AChildWhoHasStoppedPlaying",
          "beside an idle robot, the child plays for 15 s, then stops: hands in the lap, looking away for a minute",
          sentences({scheme::kNoPlay, scheme::kPassive}),
          true, 75.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 15.0);
            s.purple().look_away(59.0).at(16.0);
          },
          {mostly(kPurple, NoPlay, 25, 75), mostly(kPurple, Passive, 25, 75)}};
}

Vignette stopped_while_robot_goes_on() {
  return {"AChildWhoHasStoppedPlayingWhileTheRobotGoesOn",
          "the child stops playing at 16 s and looks away, glancing at the robot once; the robot keeps arranging its "
          "animals and says something every 10 s",
          sentences({scheme::kNoPlay, scheme::kPassive, scheme::kSolitary}),
          true, 75.0,
          [](Script& s) {
            arrange(s.robot(), {"giraffe", "hippo"}, kSecondArea, 2.0, 74.0);
            s.robot().say(Comment, 1.2).every(10.0, 5.5, 74.0);
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 15.0);
            s.purple().look_away(59.0).at(16.0);
            s.purple().look_at_partner(1.0).at(40.0);
          },
          {mostly(kPurple, NoPlay, 25, 75), mostly(kPurple, Passive, 25, 75), never(kPurple, Associative, 25, 75),
           never(kPurple, Cooperative, 25, 75)}};
}

Vignette grabbing() {
  return {"GrabbingTheOthersItem",
          "the yellow child is playing with the lion; the purple child watches, then drags the lion away to its own "
          "side without a word and plays with it",
          sentences({scheme::kAdversarial}),
          false, 45.0,
          [](Script& s) { snatch_the_lion(s.yellow(), kSecondArea, s.purple(), kPurpleArea, false, 45.0); },
          {mostly(kPurple, Adversarial, 19, 25, 0.5), never(kYellow, Adversarial, 0, 45)}};
}

Vignette asking_before_taking() {
  return {"AskingForTheLionThenTakingIt",
          "the yellow child has put the lion down 4 s ago and plays with the giraffe; the purple child asks 'can I "
          "have the lion?' and, without waiting for an answer, drags it to its side; yellow lets it be",
          sentences({scheme::kAssertive, scheme::kAdversarial}),
          false, 45.0,
          [](Script& s) {
            arrange(s.yellow(), {"lion"}, kSecondArea, 1.0, 13.0, 3.0);  // the lion rests from 14.5 s on
            arrange(s.yellow(), {"giraffe", "hippo"}, kSecondArea + Vec2{0.08, 0.0}, 16.0, 45.0);
            arrange(s.purple(), {"zebra", "girl"}, kPurpleArea, 1.0, 16.0);
            s.purple().say(Request, 1.5).at(17.0);  // "can I have the lion?"
            s.purple().drag("lion", kSecondArea, kPurpleArea, 1.5).at(18.5);
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 22.0, 45.0);
            s.yellow().look_at_partner(1.0).at(17.6);
          },
          {mostly(kPurple, Assertive, 17, 27, 0.5), never(kPurple, Adversarial, 0, 45),
           never(kYellow, Frustrated, 0, 45)}};
}

Vignette protest_after_losing() {
  return {"ProtestAfterLosingAnItem",
          "the purple child drags away the lion the yellow child was playing with; yellow protests three times "
          "('hey, that's mine!', 'give it back!') and sulks, watching, until 32 s",
          sentences({scheme::kFrustrated}),
          false, 45.0,
          [](Script& s) { snatch_the_lion(s.yellow(), kSecondArea, s.purple(), kPurpleArea, true, 45.0); },
          {mostly(kYellow, Frustrated, 21, 30, 0.6), never(kYellow, Adversarial, 0, 45)}};
}

Vignette bossy_proposals() {
  return {"BossyProposalsToThePartner",
          "the purple child tells the yellow child what to do every 4 s ('put it there!', 'no, give me the lion!'), "
          "looking at it; yellow silently does as told on its side",
          sentences({scheme::kAssertive}),
          false, 60.0,
          [](Script& s) {
            static const std::array<Utterance, 2> orders = {Request, Proposal};
            static const std::array<std::string_view, 3> items = {"giraffe", "hippo", "crocodile"};
            std::size_t k = 0;
            for (double t = 3.0; t < 58.0; t += 4.0, ++k) {
              s.purple().say(orders[k % orders.size()], 1.5).at(t);
              s.yellow().drag(items[k % items.size()], kSecondArea, kSecondArea + Vec2{-0.06, -0.02}).at(t + 2.0);
            }
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 58.0, 8.0);
          },
          {mostly(kPurple, Assertive, 10, 60)}};
}

Vignette friendly_help() {
  return {"FriendlyHelpAndPraise",
          "both children play on their own sides; the yellow child asks for help every 6 s ('where does the hippo "
          "go?') and the purple child answers kindly and praises its scene",
          sentences({scheme::kProsocial, scheme::kAssociative}),
          false, 60.0,
          [](Script& s) {
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 59.0);
            arrange(s.yellow(), {"giraffe", "hippo"}, kSecondArea, 2.5, 59.0);
            s.yellow().say(Question, 1.5).every(6.0, 4.0, 59.0);
            s.purple().look_at_partner(1.0).every(6.0, 4.5, 59.0);
            s.purple().say(Comment, 1.5).every(6.0, 5.8, 59.0);  // "in the water! it's a nice zoo"
          },
          {mostly(kPurple, Prosocial, 12, 60), mostly(kPurple, Associative, 12, 60)}};
}

Vignette robot_takes_childs_item() {
  return {"RobotTakesTheChildsItemAndTheChildProtests",
          "the robot drags away the lion the child was playing with; the child protests three times and sulks, "
          "watching, until 32 s",
          sentences({scheme::kFrustrated}),
          true, 45.0,
          [](Script& s) { snatch_the_lion(s.purple(), kPurpleArea, s.robot(), kSecondArea, true, 45.0); },
          {mostly(kPurple, Frustrated, 21, 30, 0.6), never(kPurple, Adversarial, 0, 45)}};
}

Vignette child_bosses_robot() {
  return {"ChildBossesTheRobot",
          "the child tells the robot what to do every 4 s ('put the giraffe there!'), looking at it; the robot does "
          "as told on its side",
          sentences({scheme::kAssertive}),
          true, 60.0,
          [](Script& s) {
            static const std::array<std::string_view, 3> items = {"giraffe", "hippo", "crocodile"};
            std::size_t k = 0;
            for (double t = 3.0; t < 58.0; t += 4.0, ++k) {
              s.purple().say(k % 2 == 0 ? Request : Proposal, 1.5).at(t);
              s.robot().drag(items[k % items.size()], kSecondArea, kSecondArea + Vec2{-0.06, -0.02}, 2.0).at(t + 2.0);
            }
            arrange(s.purple(), {"lion", "zebra"}, kPurpleArea, 1.0, 58.0, 8.0);
          },
          {mostly(kPurple, Assertive, 10, 60)}};
}

std::vector<Vignette> task_and_attitude_vignettes() {
  return {landscape_drawing(),
          landscape_after_one_pick(),
          animals_in_habitats(),
          scribbles(),
          silly_taps(),
          asks_experimenter(),
          stopped_playing(),
          stopped_while_robot_goes_on(),
          grabbing(),
          asking_before_taking(),
          protest_after_losing(),
          bossy_proposals(),
          friendly_help(),
          robot_takes_childs_item(),
          child_bosses_robot()};
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(TaskAndAttitude, CoderVignette, ::testing::ValuesIn(task_and_attitude_vignettes()),
                         vignette_name);

}  // namespace freeplay::agents::vignette
