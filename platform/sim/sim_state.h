/* platform/sim/sim_state.h: what a host simulation tells the image generator, whichever protocol carried it (CIGI
 * 3.3, FlightGear's generic protocol, X-Plane's RREF replies): the eyepoint, the view's frustum, the date and time,
 * the wind and the cloud layers. The protocol decoders (cigi.c, fgfs.c, xplane.c) fill it; `cumulo ig` applies it.
 * Pure data, no I/O. */
#ifndef CU_PLATFORM_SIM_STATE_H
#define CU_PLATFORM_SIM_STATE_H

/* Which parts a decoder set since the flags were last cleared (the IG clears them after applying). */
enum {
    CU_SIM_POSE = 1u << 0,     /* entity (ownship) position and attitude */
    CU_SIM_VIEW = 1u << 1,     /* the eyepoint's offset and rotation from the entity */
    CU_SIM_FRUSTUM = 1u << 2,  /* the view's half-angles */
    CU_SIM_TIME = 1u << 3,     /* date and time of day (UTC) */
    CU_SIM_WIND = 1u << 4,     /* the global wind */
    CU_SIM_LAYERS = 1u << 5    /* a cloud layer changed */
};

#define CU_SIM_LAYERS_MAX 3    /* CIGI's cloud layers 1..3 (Weather Control layer IDs) */

/* Cloud types, numbered as CIGI 3.3's Weather Control packet numbers them. */
typedef enum cu_sim_cloud_type {
    CU_SIM_CLOUD_NONE = 0, CU_SIM_CLOUD_ALTOCUMULUS, CU_SIM_CLOUD_ALTOSTRATUS, CU_SIM_CLOUD_CIRROCUMULUS,
    CU_SIM_CLOUD_CIRROSTRATUS, CU_SIM_CLOUD_CIRRUS, CU_SIM_CLOUD_CUMULONIMBUS, CU_SIM_CLOUD_CUMULUS,
    CU_SIM_CLOUD_NIMBOSTRATUS, CU_SIM_CLOUD_STRATOCUMULUS, CU_SIM_CLOUD_STRATUS
} cu_sim_cloud_type;

typedef struct cu_sim_layer {
    int enabled;
    int type;                  /* cu_sim_cloud_type (CIGI numbers 11..15 are "other": kept as given) */
    double coverage;           /* 0..1 (CIGI sends percent) */
    double base_m;             /* base elevation, metres above mean sea level */
    double thickness_m;
    double transition_m;       /* transition band, m */
    int scud;                  /* scud enable */
    double scud_frequency;     /* 0..1 */
    double wind_speed;         /* horizontal, m/s */
    double wind_from_deg;      /* direction the wind blows FROM, degrees from true north toward east */
} cu_sim_layer;

typedef struct cu_sim_state {
    unsigned changed;          /* CU_SIM_* bits */
    /* The entity the eyepoint rides on (CIGI: the ownship, entity 0; FlightGear and X-Plane: the aircraft). WGS84
     * geodetic latitude and longitude (degrees, north and east positive), altitude above mean sea level (metres);
     * attitude as aviation gives it: yaw = true heading (degrees from north toward east), pitch up positive, roll
     * right wing down positive, applied yaw, then pitch, then roll. */
    int pose_valid;
    double lat_deg, lon_deg, alt_m;
    double yaw_deg, pitch_deg, roll_deg;
    /* The eyepoint relative to the entity (CIGI View Control): offsets in the entity's body frame (x forward, y right,
     * z down, metres) and a rotation (yaw, pitch, roll, degrees) after the entity's. Zero for the others. */
    double view_xyz[3];
    double view_yaw_deg, view_pitch_deg, view_roll_deg;
    /* The frustum (CIGI View Definition): half-angles in degrees from the view axis, left and bottom negative for a
     * centred view (CIGI's signs), and the near and far planes. frustum_valid = 0: the scene's field of view. */
    int frustum_valid;
    double fov_left_deg, fov_right_deg, fov_top_deg, fov_bottom_deg;
    double near_m, far_m;
    /* Date and time of day, UTC. second may be fractional (CIGI sends minutes only: 0). */
    int time_valid;
    int year, month, day, hour, minute;
    double second;
    /* The global wind (CIGI Atmosphere Control). */
    int wind_valid;
    double wind_speed, wind_from_deg;
    cu_sim_layer layers[CU_SIM_LAYERS_MAX];
} cu_sim_state;

#endif
