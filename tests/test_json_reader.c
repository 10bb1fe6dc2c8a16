/* core/json_reader: values of every type, escapes (surrogate pairs), numbers
 * at the grammar's edges, nesting at and past the depth limit, and each kind
 * of malformed text with its line in the message. */
#include "check.h"

#include "core/json_reader.h"

static void expect_bad(const char *text, const char *msg)
{
    json_value v;
    neuv_status s = json_parse(text, strlen(text), &v);
    CHECK_INT(s, NEUV_ERR_INPUT);
    CHECK_INT(v.type, JSON_NULL);
    if (!strstr(neuv_last_error(), msg)) {
        check_failures++;
        fprintf(stderr, "'%s': message '%s' lacks '%s'\n", text, neuv_last_error(), msg);
    }
    check_count++;
}

static void test_values(void)
{
    const char *t = " {\"a\": [1, -2.5e3, 0.125, true, false, null], \"s\": \"x\\ty\\u00e9\\ud83d\\ude00\\\"\","
                    " \"o\": {}, \"e\": [], \"a\": 7}\n";
    json_value v;
    CHECK_INT(json_parse(t, strlen(t), &v), NEUV_OK);
    CHECK_INT(v.type, JSON_OBJECT);
    CHECK_INT(v.n, 5);
    long long x;
    /* A repeated key: the last one counts. */
    CHECK(json_int_in(json_get(&v, "a"), 0, 10, &x) && x == 7);
    const json_value *a = &v.items[0];
    CHECK_INT(a->type, JSON_ARRAY);
    CHECK_INT(a->n, 6);
    CHECK_NEAR(json_at(a, 1)->number, -2500, 0);
    CHECK_NEAR(json_at(a, 2)->number, 0.125, 0);
    CHECK(!json_int_in(json_at(a, 2), -10, 10, &x)); /* not an integer */
    CHECK(!json_int_in(json_at(a, 1), 0, 10, &x));   /* out of range */
    CHECK(json_at(a, 3)->type == JSON_BOOL && json_at(a, 3)->boolean == 1);
    CHECK(json_at(a, 4)->type == JSON_BOOL && json_at(a, 4)->boolean == 0);
    CHECK_INT(json_at(a, 5)->type, JSON_NULL);
    CHECK(json_at(a, 6) == NULL && json_at(a, -1) == NULL);
    const json_value *s = json_get(&v, "s");
    /* x TAB y, e-acute (2 bytes), U+1F600 (4 bytes), quote */
    CHECK_INT(s->string_len, 1 + 1 + 1 + 2 + 4 + 1);
    CHECK(!memcmp(s->string, "x\ty\xc3\xa9\xf0\x9f\x98\x80\"", s->string_len));
    CHECK(json_get(&v, "o")->type == JSON_OBJECT && json_get(&v, "o")->n == 0);
    CHECK(json_get(&v, "missing") == NULL && json_get(a, "a") == NULL);
    json_value_free(&v);
    /* Length-bounded: the text after len is not read. */
    CHECK_INT(json_parse("[1]garbage", 3, &v), NEUV_OK);
    json_value_free(&v);
}

static void test_depth(void)
{
    char deep[2 * (JSON_MAX_DEPTH + 2) + 1];
    for (int depth = JSON_MAX_DEPTH; depth <= JSON_MAX_DEPTH + 1; depth++) {
        int n = depth + 1; /* the outermost array is at depth 0 */
        for (int i = 0; i < n; i++) { deep[i] = '['; deep[n + i] = ']'; }
        deep[2 * n] = '\0';
        json_value v;
        neuv_status s = json_parse(deep, strlen(deep), &v);
        CHECK_INT(s, depth <= JSON_MAX_DEPTH ? NEUV_OK : NEUV_ERR_INPUT);
        json_value_free(&v);
    }
}

static void test_malformed(void)
{
    expect_bad("", "unexpected end");
    expect_bad("[1,]", "unexpected character");
    expect_bad("{\"a\" 1}", "expected ':'");
    expect_bad("{1: 2}", "expected a key");
    expect_bad("[1 2]", "expected ',' or ']'");
    expect_bad("{\"a\": 1,\n\n\"b\" }", "line 3");
    expect_bad("\"abc", "unterminated string");
    expect_bad("\"a\nb\"", "control character");
    expect_bad("\"\\x\"", "bad escape");
    expect_bad("\"\\u12\"", "bad \\u escape");
    expect_bad("\"\\ud800x\"", "unpaired surrogate");
    expect_bad("\"\\udc00\"", "unpaired surrogate");
    expect_bad("01", "text after the value");
    expect_bad("1.", "bad number");
    expect_bad("-", "bad number");
    expect_bad("1e", "bad number");
    expect_bad("+1", "unexpected character");
    expect_bad("1e999", "out of range");
    expect_bad("nul", "unexpected character");
    expect_bad("[1] [2]", "text after the value");
}

int main(void)
{
    test_values();
    test_depth();
    test_malformed();
    return check_report("test_json_reader");
}
