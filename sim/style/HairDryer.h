#pragma once
// The blow-dryer of Ward et al.'s virtual salon: a cone of moving air from the cursor along the
// view direction. It pushes the strands inside it (a wind of their own) and dries them.

#include <glm/vec3.hpp>

namespace wisp {

class SignedDistanceField;

struct HairDryer {
    glm::vec3 nozzle{ 0.0f }; // world, metres: where the air leaves the dryer
    glm::vec3 direction{ 0.0f, 0.0f, -1.0f }; // unit, world
    float halfAngleRadians = 0.35f; // the cone's opening
    float speedMetresPerSecond = 12.0f; // on the axis, at the nozzle (a salon dryer: 10-15)
    float reachMetres = 1.0f; // no air beyond this distance along the axis
};

// The dryer's air velocity at `p` (m/s, world). Inside the cone the speed falls off with the
// angle from the axis (cos² of angle / half angle · π/2, zero at the edge) and with distance
// along it (a free jet slows about as 1 / (1 + d / 0.3 m)); zero outside the cone, behind the
// nozzle or beyond its reach.
glm::vec3 dryerAirAt(const HairDryer& dryer, const glm::vec3& p);
// The same where the head does not stand between the nozzle and p (the jet does not pass through
// the head): the segment from the nozzle to p (less its last centimetre: hair lies on the skin) is
// sphere-traced through the head's distance field. `head` null: no occlusion.
glm::vec3 dryerAirAt(const HairDryer& dryer, const glm::vec3& p, const SignedDistanceField* head);

// Water lost per second at air speed `airSpeed` (m/s) by hair of wetness w: still air dries with
// half-life `halfLifeSeconds`; moving air adds 0.25 per (m/s) per second, so a dryer at 4 m/s dries
// soaked hair in about a second (returns the rate dw/dt <= 0).
float dryingRate(float wetness, float airSpeed, float halfLifeSeconds);

// Wet hair (Ward et al.; Bertails et al. 2006): water makes hair heavier, so the same air moves it
// less; softer, so curls relax under their own weight; and it sticks together, so wisps clump.
float wetStiffnessFactor(float wetness); // multiplies the bending stiffness: 1 dry, 0.25 soaked
float wetDragFactor(float wetness); // multiplies the drag toward the wind: 1 dry, 0.4 soaked
float wetVolumeFactor(float wetness); // multiplies the density hair keeps (volume grid): 1 dry, 3 soaked, so wet hair
                                      // takes a third of the room
float wetClumping(float wetness); // pulls the clump degree toward 1 (and the clump start toward the root) by this
                                  // share: 0 dry, 1 soaked

} // namespace wisp
