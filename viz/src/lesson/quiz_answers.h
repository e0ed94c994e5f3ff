// The quiz's calls into core (question.h), in one place: the answer computed from the walk or the build,
// whether a typed prediction matches it, and a wrong one's feedback.
#pragma once

#include "raystep/lesson/question.h"

namespace raystep::viz {

inline Answer computeAnswer(QuestionKind kind, const QuestionContext& context) {
  return answer_question(kind, context);
}
inline bool predictionMatches(const Answer& answer, const std::string& prediction) {
  return prediction_matches(answer, prediction);
}
inline std::string predictionFeedback(const Answer& answer, const std::string& prediction) {
  return prediction_feedback(answer, prediction);
}

}  // namespace raystep::viz
