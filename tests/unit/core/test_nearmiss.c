/* test_nearmiss.c - "did you mean": the edit distance, and which known word a mistyped one
 * is close to. */
#include "envtex/core/nearmiss.h"

#include <string.h>

#include "unit.h"

START_TEST(test_nearmiss_distance_counts_each_edit_once)
{
    ck_assert_int_eq(nearmiss_distance("sphere", "sphere"), 0);
    ck_assert_int_eq(nearmiss_distance("sphre", "sphere"), 1);   /* a letter left out */
    ck_assert_int_eq(nearmiss_distance("spherre", "sphere"), 1); /* one too many */
    ck_assert_int_eq(nearmiss_distance("sphare", "sphere"), 1);  /* one wrong */
    ck_assert_int_eq(nearmiss_distance("shpere", "sphere"), 1);  /* two neighbours swapped */
    ck_assert_int_eq(nearmiss_distance("", "abc"), 3);
    ck_assert_int_eq(nearmiss_distance("kitten", "sitting"), 3);
    ck_assert_int_eq(nearmiss_distance("ca", "abc"), 3); /* a swap is not edited again */
}
END_TEST

START_TEST(test_nearmiss_distance_refuses_words_past_the_limit)
{
    char longword[NEARMISS_MAX_LEN + 2];
    memset(longword, 'a', sizeof longword - 1);
    longword[sizeof longword - 1] = '\0';
    ck_assert_int_eq(nearmiss_distance(longword, "a"), NEARMISS_MAX_LEN + 1);
    longword[NEARMISS_MAX_LEN] = '\0'; /* exactly the limit: measured */
    ck_assert_int_eq(nearmiss_distance(longword, longword), 0);
}
END_TEST

static const char *best_of(const char *word, const char *const *known)
{
    nearmiss m;
    nearmiss_start(&m, word);
    for (; *known; known++) nearmiss_offer(&m, *known);
    return nearmiss_best(&m);
}

START_TEST(test_nearmiss_finds_the_course_s_commands_and_envtex_s_options)
{
    const char *commands[] = {"size", "camera", "sphere", "tri", "vertex", "maxverts", NULL};
    const char *subcommands[] = {"render", "compare", "tonemap", "convert", NULL};
    const char *options[] = {"-o", "--spp", "--seed", "--ref", "--strict", NULL};
    ck_assert_str_eq(best_of("sphre", commands), "sphere");
    ck_assert_str_eq(best_of("maxvert", commands), "maxverts");
    ck_assert_str_eq(best_of("rendr", subcommands), "render");
    ck_assert_str_eq(best_of("--sppp", options), "--spp");
    ck_assert_str_eq(best_of("--sed", options), "--seed");
}
END_TEST

START_TEST(test_nearmiss_stays_silent_when_nothing_is_close)
{
    const char *commands[] = {"size", "camera", "sphere", "tri", NULL};
    ck_assert_ptr_null(best_of("sphere", commands));   /* the word itself */
    ck_assert_ptr_null(best_of("cylinder", commands)); /* far from all */
    ck_assert_ptr_null(best_of("tr", commands));       /* too short to guess */
    ck_assert_ptr_null(best_of("sz", commands));
    ck_assert_str_eq(best_of("spxxre", commands), "sphere"); /* 2 edits in 6 letters: close */
    ck_assert_ptr_null(best_of("sxxxre", commands));         /* 3 edits */
    ck_assert_ptr_null(best_of("szxe", commands));           /* 2 edits in 4 letters */
}
END_TEST

START_TEST(test_nearmiss_keeps_the_first_of_equally_close_words)
{
    const char *known[] = {"cat", "bat", "rat", NULL};
    ck_assert_str_eq(best_of("hat", known), "cat");
}
END_TEST

Suite *nearmiss_suite(void)
{
    Suite *s = suite_create("nearmiss");
    TCase *tc = tcase_create("core");
    tcase_add_test(tc, test_nearmiss_distance_counts_each_edit_once);
    tcase_add_test(tc, test_nearmiss_distance_refuses_words_past_the_limit);
    tcase_add_test(tc, test_nearmiss_finds_the_course_s_commands_and_envtex_s_options);
    tcase_add_test(tc, test_nearmiss_stays_silent_when_nothing_is_close);
    tcase_add_test(tc, test_nearmiss_keeps_the_first_of_equally_close_words);
    suite_add_tcase(s, tc);
    return s;
}

UNIT_MAIN(nearmiss_suite)
