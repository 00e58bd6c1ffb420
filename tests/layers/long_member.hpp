// The function-length check must see a member defined inside its class, indented, as
// layers.function_length_check_catches_a_long_member checks: this one is over 100 lines.
// Only that check reads this file; nothing compiles it.
#pragma once

namespace iblab::app {

class LongMember {
public:
    int sum() const
    {
        int total = 0;
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        total += values_[4];
        total += values_[5];
        total += values_[6];
        total += values_[7];
        total += values_[0];
        total += values_[1];
        total += values_[2];
        total += values_[3];
        return total;
    }

private:
    int values_[8] = {};
};

} // namespace iblab::app
